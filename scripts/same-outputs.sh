#!/usr/bin/env bash
# Proves that a change altered no user-visible output: runs the shipped experiments, the
# fleet experiments, the smoke and ablation-smoke grids (with their reports) and a few
# `covga eval` calls with the binary of BASE (default: HEAD) and with the working tree's, then
# compares every file byte for byte, timings aside (`wall_s` in JSON and CSV, the report's
# wall-time lines).
#
#   scripts/same-outputs.sh [BASE]          # e.g. scripts/same-outputs.sh 917f148
#   BASE_BIN=path/to/covga scripts/same-outputs.sh   # a binary of the base already built
#   BASE_FILES=REV scripts/same-outputs.sh  # the base binary runs the experiment and grid files
#                                           # of REV (a change that moves keys: each binary
#                                           # reads the files written for it)
#
# Exits 0 when every output file is identical, 1 (listing the files) otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
base_rev=${1:-HEAD}
work=$(realpath -m "${SAME_OUTPUTS_DIR:-target/same-outputs}")
rm -rf "$work"
mkdir -p "$work"
if [ -n "${BASE_BIN:-}" ]; then
  cp "$BASE_BIN" "$work/covga-base"
  base_rev="$BASE_BIN"
else
  git worktree remove --force "$work/base-src" 2>/dev/null || true
  git worktree add --detach "$work/base-src" "$base_rev" >/dev/null
  # The base's build folder is kept between calls to save time.
  (cd "$work/base-src" && cargo build --release --quiet --bin covga --target-dir ../../same-outputs-base-target)
  cp target/same-outputs-base-target/release/covga "$work/covga-base"
  git worktree remove --force "$work/base-src"
  base_rev=$(git rev-parse --short "$base_rev")
fi
cargo build --release --quiet --bin covga
cp "${CARGO_TARGET_DIR:-target}/release/covga" "$work/covga-new"

outputs() { # $1 binary, $2 output folder
  local bin=$1 out=$2
  mkdir -p "$out"
  for f in experiments/*.toml "$work"/extra/*.toml; do
    "$bin" run "$f" --out "$out/run/$(basename "$f" .toml)" --quiet
  done
  "$bin" eval --fleet experiments/fleets/thesis1-hetero.toml --divide --json --out "$out/eval/fleet-divide" > "$out/eval-fleet-divide.json"
  "$bin" eval --map thesis-2 --pattern spiral --json --out "$out/eval/spiral" > "$out/eval-spiral.json"
  "$bin" eval --map experiments/maps/office.yaml --start 2,2 --pattern boustrophedon --json --out "$out/eval/office" > "$out/eval-office.json"
  for g in smoke ablation-smoke; do
    "$bin" grid "grids/$g.toml" --jobs 2 --out "$out/grid/$g" > /dev/null 2>&1
    "$bin" report "$out/grid/$g" > /dev/null 2>&1
  done
}

# The fleet modes the shipped experiments do not show: area division and a waypoint team.
mkdir -p "$work/extra"
sed 's/mode = "negotiate"/mode = "divide"/' experiments/fleet-thesis1-hetero.toml > "$work/extra/fleet-divide.toml"
cat > "$work/extra/fleet-waypoint.toml" <<'TOML'
planner = "waypoint"
[map]
source = "office"
[waypoint]
generations = 30
[fleet]
mode = "waypoint"
[[robots]]
name = "a"
start = [2.0, 2.0]
[[robots]]
name = "b"
start = [2.0, 3.0]
TOML
# Every parent-selection scheme of both GAs that draw parents (the registry of ga::parents).
for scheme in elite tournament prws rrws; do
  cat > "$work/extra/cell-order-$scheme.toml" <<TOML
planner = "cell_order"
seed = 5
[map]
source = "thesis-2"
[stations]
start = [1.3, 1.3]
[cell_order]
selection = "$scheme"
population = 30
select = 8
[budget]
evaluations = 3000
TOML
done
for scheme in prws rrws; do
  cat > "$work/extra/thesis-$scheme.toml" <<TOML
planner = "thesis"
seed = 6
[map]
source = "thesis-1"
[thesis]
selection = "$scheme"
selection_pressure = 1.6
pop_min = 30
init_individuals = 60
[budget]
iterations = 40
TOML
done
echo "base: $base_rev${BASE_FILES:+ on the files of $BASE_FILES}; new: the working tree"
if [ -n "${BASE_FILES:-}" ]; then
  git worktree add --detach "$work/base-files" "$BASE_FILES" >/dev/null
  (cd "$work/base-files" && outputs "$work/covga-base" "$work/base")
  git worktree remove --force "$work/base-files"
else
  outputs "$work/covga-base" "$work/base"
fi
outputs "$work/covga-new" "$work/new"

python3 - "$work/base" "$work/new" <<'PY'
import csv, io, json, os, re, sys
base, new = sys.argv[1], sys.argv[2]

TIMINGS = {"wall_s", "precompute_s"}  # seconds of wall time, different in every run
# Which build wrote a study (its commit) and which process holds a folder differ by design.
PROVENANCE = {"git_commit"}

def strip_md(text, root):
    """A report without its timings: the study folder's name, the columns from `wall s` on,
    and the sections on run durations."""
    out, cut, skip = [], None, False
    for line in text.replace(root, "STUDY").split("\n"):
        if line.startswith("#"):
            skip = "duration" in line.lower() and "front" not in line.lower()
            cut = None
        if skip:
            continue
        if line.startswith("|"):
            cells = line.split("|")
            if cut is None and any(c.strip().startswith("wall s") for c in cells):
                cut = next(k for k, c in enumerate(cells) if c.strip().startswith("wall s"))
            if cut is not None:
                line = "|".join(cells[:cut])
        else:
            cut = None
        out.append(line)
    return "\n".join(out).encode()

def normal(path, root):
    data = open(path, "rb").read()
    if path.endswith(".json"):
        try:
            obj = json.loads(data)
        except ValueError:
            return data
        def strip(o):
            if isinstance(o, dict):
                return {k: strip(v) for k, v in o.items() if k not in TIMINGS | PROVENANCE}
            if isinstance(o, list):
                return [strip(v) for v in o]
            return o
        return json.dumps(strip(obj), sort_keys=True).encode()
    if path.endswith(".csv"):
        rows = list(csv.reader(io.StringIO(data.decode())))
        if rows:
            keep = [k for k, h in enumerate(rows[0]) if h not in TIMINGS]
            rows = [[r[k] for k in keep if k < len(r)] for r in rows]
        return repr(rows).encode()
    if path.endswith(".md"):
        return strip_md(data.decode(), root)
    return data

def files(root):
    """The output files, without the folder locks (`.covga.lock`, which name the process)."""
    out = set()
    for d, _, fs in os.walk(root):
        for f in fs:
            if f != ".covga.lock":
                out.add(os.path.relpath(os.path.join(d, f), root))
    return out

a, b = files(base), files(new)
bad = sorted(a ^ b)
for f in sorted(a & b):
    if normal(os.path.join(base, f), base) != normal(os.path.join(new, f), new):
        bad.append(f)
print(f"{len(a | b)} files compared, {len(bad)} differ")
for f in bad:
    print("  differs:", f)
sys.exit(1 if bad else 0)
PY
