#!/usr/bin/env bash
# The floor-plan benchmark of the waypoint planner: experiments/olson-ring.toml (000's values
# typed as they are on the office-ring preset) and named variants, 5 seeds each, one run at a
# time so that the times are those of one process. Writes results/olson-ring/summary.md.
#   usage: scripts/olson-ring-bench.sh [work folder]   (default /tmp/olson-ring-bench)
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-/tmp/olson-ring-bench}
mkdir -p "$work"
cargo build --release --quiet
covga=target/release/covga
base=experiments/olson-ring.toml
# name | keys added to [waypoint]
variants=(
  "paper|"
  "paper, fan view|view_shape = \"fan\""
  "paper, l_max 400|l_max = 400"
  "driver grid|grid_step = \"hallway\""
  "driver grid, near-wall set|grid_step = \"hallway\"\nwaypoint_set = \"near_wall\""
  "paper, 3 agents|agents = 3"
  "driver grid, 3 agents|grid_step = \"hallway\"\nagents = 3"
)
for v in "${variants[@]}"; do
  name=${v%%|*}; keys=${v#*|}
  tag=$(echo "$name" | tr -c 'a-z0-9\n' '-')
  sed "s/^\[waypoint\]$/[waypoint]\n$keys/" "$base" > "$work/$tag.toml"
  for seed in 1 2 3 4 5; do
    "$covga" run "$work/$tag.toml" --seed "$seed" --quiet --out "$work/$tag-$seed" 2>/dev/null
  done
done
python3 - "$work" "${variants[@]}" > results/olson-ring/summary.md <<'PY'
import csv, json, statistics as st, sys
work, variants = sys.argv[1], sys.argv[2:]
print("# Waypoint planner on the office-ring floor plan (000's values typed as they are)\n")
print("Made by `scripts/olson-ring-bench.sh` from `experiments/olson-ring.toml` (hallway 2.5 m, d_max 7 m,")
print("69.4°, 15 sections, max traverse 4 m, Table I GA values, 200 generations), seeds 1–5, one run at")
print("a time on 2 cores. Walls = best wall coverage of the population's chosen plan at generation g")
print("(history.csv `best_walls`); medians over the seeds, [min, max] beside them.\n")
print("| variant | waypoints | set-up s | ms / generation | walls g50 | walls g100 | walls g200 | feasible | team connected |")
print("|---|---|---|---|---|---|---|---|---|")
def m(xs):
    return f"{st.median(xs):.3f} [{min(xs):.3f}, {max(xs):.3f}]"
for v in variants:
    name = v.split("|")[0]
    tag = "".join(c if c in "abcdefghijklmnopqrstuvwxyz0123456789" else "-" for c in name)
    runs = []
    for seed in range(1, 6):
        d = f"{work}/{tag}-{seed}"
        s = json.load(open(f"{d}/summary.json"))
        w = {int(r["iteration"]): float(r["best_walls"]) for r in csv.DictReader(open(f"{d}/history.csv"))}
        runs.append((s, w))
    s0 = runs[0][0]
    setup = st.median(s["precompute_s"] for s, _ in runs)
    gen = st.median(1000 * (s["wall_s"] - s["precompute_s"]) / s["iterations"] for s, _ in runs)
    feas = sum(1 for s, _ in runs if s["feasible"])
    team = "—" if s0["agents"] == 1 else f"{sum(1 for s, _ in runs if s['connected'])}/5"
    cols = [m([w[g] for _, w in runs]) for g in (50, 100, 200)]
    print(f"| {name} | {s0['waypoints']} | {setup:.2f} | {gen:.1f} | {' | '.join(cols)} | {feas}/5 | {team} |")
PY
cat results/olson-ring/summary.md
