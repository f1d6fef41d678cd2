#!/usr/bin/env bash
# Records where CI's time goes: clones this checkout's HEAD into a fresh folder and runs
# `bash .ci/run` there cold (no target/, and an empty $COVGA_CACHE: no Python environment, no
# mdbook), as CI does on a clean clone, with every step's wall time logged (scripts/steps.sh).
# Writes the table to tests/suite-times.md (or the file given as $1) and exits with CI's
# status. What a cold clone still finds on the machine is said in the file: crates.io's
# downloads in ~/.cargo and Debian's Slurm packages, once installed, stay installed.
#
#   bash scripts/suite-times.sh            # commit first: the clone is of HEAD
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-tests/suite-times.md}"
work=$(mktemp -d /tmp/covga-suite-times.XXXXXX)
trap 'rm -rf "$work"' EXIT
git clone --quiet --no-hardlinks . "$work/covga"
commit=$(git rev-parse --short HEAD)
log="$work/steps.tsv"
slurm_before=$(command -v slurmctld >/dev/null && echo "installed before the run" || echo "installed by the run")
start=$(date +%s.%N)
status=0
(cd "$work/covga" && CI=true COVGA_STEP_LOG="$log" COVGA_CACHE="$work/cache" bash .ci/run) >"$work/ci.log" 2>&1 || status=$?
total=$(awk "BEGIN { printf \"%.0f\", $(date +%s.%N) - $start }")
[ "$status" = 0 ] || { tail -n 60 "$work/ci.log" >&2; echo "CI failed (exit $status)" >&2; }

{
  echo "# CI times"
  echo
  echo "Written by \`bash scripts/suite-times.sh\` on $(nproc) cores, $(date -u +%Y-%m-%d), commit $commit:"
  echo "\`bash .ci/run\` in a fresh clone, cold (no \`target/\`, no Python environment, no mdbook;"
  echo "crates.io's downloads cached in \`~/.cargo\`; Slurm's Debian packages $slurm_before)."
  echo "Wall seconds per step, as \`.ci/run\` prints them (\`::: step NAME: S s\`)."
  echo
  echo "**Cold clean-clone CI total: $total s ($(awk "BEGIN { printf \"%.1f\", $total / 60 }") min), $([ "$status" = 0 ] && echo "every step passing" || echo "failed, exit $status").**"
  echo
  echo "| step | seconds | minutes | status |"
  echo "|---|---:|---:|---|"
  awk -F'\t' '{ printf "| %s | %.1f | %.1f | %s |\n", $1, $2, $2 / 60, $3 }' "$log"
  # Each Rust test binary's own time within rust-tests, from the test harness's summary lines.
  awk '/^ *Running /{ name = ($2 == "unittests") ? $2 " " $3 : $2 } /^test result:/ && name != "" {
         for (i = 1; i <= NF; i++) if ($i == "in") secs = $(i + 1); sub(/s$/, "", secs);
         printf "| rust-tests: %s, %s | %.1f | %.1f | |\n", name, $4 " tests", secs, secs / 60; name = "" }' "$work/ci.log"
  echo "| **CI in all** | **$total** | **$(awk "BEGIN { printf \"%.1f\", $total / 60 }")** | $([ "$status" = 0 ] && echo ok || echo "exit $status") |"
  echo
  echo "The steps: \`fmt\`, \`clippy\` (\`--workspace --all-targets\`), \`rustdoc\`; \`book\` (scripts/book.sh) runs"
  echo "in the background beside scripts/test.sh (its time overlaps the others; \`book-wait\` is what"
  echo "CI waited for it at the end); scripts/test.sh: \`build\` (one release build, no debug info, of every test binary, the"
  echo "binary and the library the Python extension links), \`rust-tests\` (\`--tests\`: the unit tests, tests/it,"
  echo "and tests/replays with one test per committed study, run side by side; each binary's own time"
  echo "is a row of its own), \`python\`"
  echo "(scripts/python-tests.sh: the wheel, mypy, pytest; \`python-env\` is what was left of the"
  echo "environment's install, started in the background when scripts/test.sh began) and \`slurm\`"
  echo "(likewise \`slurm-install\`). The rows overlapping others are not added up: **CI in all** is"
  echo "the wall time from start to end."
} >"$out"
echo "wrote $out"
exit "$status"
