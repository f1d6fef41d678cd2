#!/usr/bin/env bash
# Integration test against a real Slurm: install it, start a single-node cluster, submit the
# smoke grid as a job array, wait, merge, and check the merged runs.csv equals a local run of
# the same grid (same ids and metrics; wall_s aside). Stops the daemons it started.
set -euo pipefail
cd "$(dirname "$0")/../.."
covga=${COVGA:-target/release/covga}
[ -x "$covga" ] || cargo build --release --quiet
covga=$(cd "$(dirname "$covga")" && pwd)/$(basename "$covga")

scripts/slurm-local.sh install
work=$(mktemp -d /tmp/covga-slurm.XXXXXX)
cluster="$work/cluster"
cleanup() { scripts/slurm-local.sh stop "$cluster" || true; }
trap cleanup EXIT

SLURM_CONF=$(scripts/slurm-local.sh start "$cluster" | tail -n 1)
export SLURM_CONF

# The smoke grid with its map as a path relative to the repository (where the script is
# written), submitted from another folder: the tasks must read the map where it was meant.
grid="$work/smoke-relative.toml"
sed 's|^source = "thesis-1"$|source = "experiments/maps/thesis-1.yaml"|' grids/smoke.toml > "$grid"
grep -q 'experiments/maps/thesis-1.yaml' "$grid"
study="$work/slurm-study"
"$covga" grid "$grid" --slurm --array-size 4 --time 00:10:00 --cpus-per-task 1 --out "$study"
job=$(cd "$work" && sbatch --parsable "$study/study.sbatch")
job=${job%%;*}
echo "submitted array job $job"
end=$((SECONDS + 600))
while [ -n "$(timeout 5 squeue -h -j "$job" 2>/dev/null || true)" ]; do
  if [ "$SECONDS" -ge "$end" ]; then echo "array job $job did not finish in 600 s" >&2; exit 1; fi
  sleep 1
done
states=$(timeout 5 scontrol show job "$job" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | sort | uniq -c || true)
echo "task states: $states"
if echo "$states" | grep -qvE 'COMPLETED'; then
  echo "some tasks did not complete:" >&2
  cat "$study"/slurm/*.out >&2 || true
  exit 1
fi
shards=$(ls "$study"/runs-shard-*-of-4.csv | wc -l)
[ "$shards" -eq 4 ] || { echo "expected 4 shard files, found $shards" >&2; exit 1; }
"$covga" merge "$study"

local_study="$work/local-study"
"$covga" grid "$grid" --jobs 2 --out "$local_study" >/dev/null 2>&1

strip() { # drop the wall_s column
  python3 - "$1" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
w = rows[0].index("wall_s")
for r in sorted(rows[1:]):
    print(",".join(v for i, v in enumerate(r) if i != w))
PY
}
if ! diff <(strip "$study/runs.csv") <(strip "$local_study/runs.csv") >/dev/null; then
  echo "merged Slurm runs.csv differs from the local run" >&2
  diff <(strip "$study/runs.csv") <(strip "$local_study/runs.csv") | head >&2
  exit 1
fi
n=$(($(wc -l < "$study/runs.csv") - 1))
echo "slurm array job: $n runs via a 4-task array equal the local run"
echo "slurm: 1 passed, 0 failed"
