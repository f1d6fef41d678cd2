#!/usr/bin/env bash
# Mutation testing of covga's core with cargo-mutants: every mutant of the core modules is
# built and the test suite run against it; a mutant that no test notices is "missed".
# Not in CI (hours for the whole core on two cores). Mutants judged equivalent or unreachable
# are excluded in .cargo/mutants.toml, each with its reason.
#
#   scripts/mutants.sh                              # the whole core, whole test suite
#   scripts/mutants.sh --file src/ga/selection.rs   # one module
#   scripts/mutants.sh --in-diff <(git diff main)   # only mutants on changed lines
#   MUTANTS_TESTS=lib scripts/mutants.sh …          # library tests only (faster, weaker)
#
# Results: target/mutants/mutants.out/{caught,missed,timeout,unviable}.txt
set -euo pipefail
cd "$(dirname "$0")/.."
command -v cargo-mutants >/dev/null || cargo install cargo-mutants --locked
core=(
  src/coverage/bits.rs src/coverage/rows.rs src/coverage/raster.rs src/coverage/sweep.rs src/coverage/score.rs
  src/thesis/fitness.rs src/thesis/crossover.rs src/thesis/mutation.rs src/thesis/genome.rs
  src/thesis/individual.rs src/thesis/diversity.rs src/thesis/architecture.rs
  src/ga/selection.rs src/ga/control.rs src/ga/pareto.rs src/ga/rng.rs src/ga/maximin.rs
  src/waypoint/evaluate.rs src/waypoint/operators.rs
  src/study/stats.rs src/study/report.rs
)
files=()
if [[ " $* " != *" --file "* && " $* " != *" --in-diff "* ]]; then
  for f in "${core[@]}"; do files+=(--file "$f"); done
fi
# The test profile (opt-level 2 in Cargo.toml) serves both the build check and the tests,
# so each mutant is compiled once.
test_args=()
if [ "${MUTANTS_TESTS:-all}" = lib ]; then test_args+=(--lib); fi
exec cargo mutants "${files[@]}" --output target/mutants --timeout-multiplier 3 "$@" -- "${test_args[@]}"
