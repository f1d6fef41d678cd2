#!/usr/bin/env bash
# Mutation testing of covga's core with cargo-mutants: every mutant of the core modules is
# built and tested; a mutant that no test notices is "missed".
# Not in CI (hours for the whole core on two cores). Mutants judged equivalent or
# unreachable are excluded in .cargo/mutants.toml, each with its reason.
#
# Two stages, one output folder, resumable (stop it at any point and run it again):
#   1. every mutant against the library's unit tests (one test binary: ~7 s a mutant);
#   2. the mutants stage 1 missed or timed out, against the whole test suite (every test
#      binary, the end-to-end tests included).
# A mutant the unit tests catch is caught by the whole suite, so the two stages together give
# the verdict of the whole suite on every mutant. Both stages run with --iterate: mutants
# already caught or unviable are skipped, so a run stopped part-way carries on where it was.
#
#   scripts/mutants.sh                              # the whole core
#   scripts/mutants.sh --file src/ga/selection.rs   # one module
#   scripts/mutants.sh --in-diff <(git diff main)   # only mutants on changed lines
#   MUTANTS_OUT=target/mutation-x scripts/mutants.sh # another output folder
#   MUTANTS_STAGES=all scripts/mutants.sh …         # skip stage 1 (whole suite only)
#   scripts/mutants.sh --check-pins                 # every pinned exclusion still names a mutant
#
# Results: $MUTANTS_OUT/mutants.out/{caught,previously_caught,missed,timeout,unviable}.txt and a
# summary line at the end. Start again from nothing: rm -r target/mutation.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v cargo-mutants >/dev/null || cargo install cargo-mutants --locked
# The core, one file a path (tests/it/mutation_tooling.rs checks that each is there, and that
# every pin of .cargo/mutants.toml names a file, a function and an operator that are there).
core=(
  src/coverage/bits.rs src/coverage/planes.rs src/coverage/rows.rs src/coverage/raster.rs src/coverage/sweep.rs src/coverage/score.rs
  src/coverage/views.rs src/coverage/fitness.rs
  src/thesis/segments.rs src/thesis/lanes.rs src/thesis/crossover.rs src/thesis/mutation.rs src/thesis/genome.rs
  src/thesis/individual.rs src/thesis/diversity.rs src/thesis/architecture.rs
  src/ga/selection.rs src/ga/control.rs src/ga/pareto.rs src/ga/rng.rs src/ga/maximin.rs
  src/waypoint/evaluate.rs src/waypoint/operators.rs
  src/stats/describe.rs src/stats/rank_sum.rs src/stats/kruskal.rs src/stats/effect.rs src/stats/family.rs
  src/stats/paired.rs src/report/analysis/runs.rs
)
if [ "${1:-}" = "--check-pins" ]; then
  # A pin (`file:line:column: …` in .cargo/mutants.toml) goes stale when its line moves, and the
  # mutant it meant is then tested again (and reported missed). Lists the pinned files' mutants
  # without the exclusions and names every pin that matches none of them.
  list=$(mktemp)
  mapfile -t pinned < <(grep -o '"src/[^:"]*' .cargo/mutants.toml | tr -d '"' | sort -u)
  cargo mutants --list --no-config "${pinned[@]/#/--file=}" > "$list"
  stale=0
  while IFS= read -r pin; do
    grep -qE -- "$pin" "$list" || { echo "stale pin: $pin"; stale=1; }
  done < <(grep -o '"src/[^"]*"' .cargo/mutants.toml | sed 's/^"//; s/"$//; s/\\\\/\\/g')
  rm "$list"
  [ "$stale" = 0 ] && echo "pins: all ${#pinned[@]} pinned files checked, none stale"
  exit "$stale"
fi
out=${MUTANTS_OUT:-target/mutation}
files=()
if [[ " $* " != *" --file "* && " $* " != *" --in-diff "* ]]; then
  for f in "${core[@]}"; do files+=(--file "$f"); done
fi
mkdir -p "$out"
# The `mutants` profile (Cargo.toml: the test profile without local ThinLTO) serves both the
# build and the tests, so each mutant is compiled once per stage; an incremental rebuild takes
# seconds (a dozen with ThinLTO, which also fails to link now and then).
# --iterate folds the unviable mutants of earlier passes into previously_caught.txt; a ledger
# kept here, read before every pass, keeps them apart for the figures.
m="$out/mutants.out"
ledger="$out/unviable-all.txt"
keep_unviable() { cat "$m/unviable.txt" "$ledger" 2>/dev/null | sort -u > "$ledger.new" || true; mv "$ledger.new" "$ledger"; }
run() {
  keep_unviable
  cargo mutants "${files[@]}" --output "$out" --iterate --profile mutants "$@"
}
# cargo-mutants exits 0 (all caught), 2 (some missed) or 3 (some timed out) after a whole pass;
# anything else (an interruption, a failing baseline) leaves the stage to be run again.
finished() { [ "$1" = 0 ] || [ "$1" = 2 ] || [ "$1" = 3 ]; }
stage_lib="$out/stage-lib.done"
if [ "${MUTANTS_STAGES:-lib,all}" = "lib,all" ] && [ ! -e "$stage_lib" ]; then
  rc=0
  run --cargo-arg=--lib "$@" || rc=$?
  finished "$rc" || exit "$rc"
  touch "$stage_lib"
fi
rc=0
run "$@" || rc=$?
finished "$rc" || exit "$rc"
keep_unviable
# The figures: previously_caught.txt holds what earlier passes caught (and found unviable),
# caught.txt this pass.
count() { cat "$@" 2>/dev/null | sort -u | grep -c . || true; }
caught=$(cat "$m/caught.txt" "$m/previously_caught.txt" 2>/dev/null | sort -u | grep -vxF -f "$ledger" | grep -c . || true)
missed=$(count "$m/missed.txt")
timeout=$(count "$m/timeout.txt")
unviable=$(count "$ledger")
tested=$((caught + missed + timeout))
echo "mutants: $tested tested (unviable $unviable left out): caught $caught, timed out $timeout, missed $missed;" \
  "kill rate $(awk -v c="$caught" -v t="$timeout" -v n="$tested" 'BEGIN { if (n) printf "%.1f %%", 100 * (c + t) / n; else print "n/a" }')"
exit "$rc"
