#!/usr/bin/env bash
# The test suite, part by part, with each part's wall time: the unit tests (`--lib`, `--bins`),
# every module of the integration binary `tests/it` and of the heavy replays `tests/replays`.
# Writes the table to tests/suite-times.md (or the file given as $1) and exits non-zero when a
# part fails. Together the parts are `cargo test --release`; run on the machine the table names.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-tests/suite-times.md}"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT

build_start=$(date +%s.%N)
cargo test --release --no-run --quiet 2>>"$log"
build_s=$(awk "BEGIN { print $(date +%s.%N) - $build_start }")

rows=""
fast_s=0
heavy_s=0
failed=0
# Runs one part; adds a row "| part | tests | seconds |".
part() {
  local name="$1" kind="$2"
  shift 2
  local start end secs passed
  start=$(date +%s.%N)
  if ! cargo test --release --quiet "$@" >"$log.part" 2>&1; then
    failed=1
    echo "FAILED: $name" >&2
    cat "$log.part" >&2
  fi
  end=$(date +%s.%N)
  secs=$(awk "BEGIN { print $end - $start }")
  passed=$(grep -o '[0-9]* passed' "$log.part" | awk '{s += $1} END {print s + 0}')
  rows+="| \`$name\` | $passed | $(printf '%.1f' "$secs") |"$'\n'
  if [ "$kind" = fast ]; then fast_s=$(awk "BEGIN { print $fast_s + $secs }"); else heavy_s=$(awk "BEGIN { print $heavy_s + $secs }"); fi
  printf '%-28s %4s tests %7.1f s\n' "$name" "$passed" "$secs"
}

modules() { sed -n 's/^mod \([a-z_0-9]*\);$/\1/p' "$1" | grep -v '^common$'; }

part "--lib" fast --lib
part "--bins" fast --bins
for m in $(modules tests/it/main.rs); do part "it $m" fast --test it -- "$m::"; done
for m in $(modules tests/replays/main.rs); do part "replays $m" heavy --test replays -- "$m::"; done
rm -f "$log.part"

{
  echo "# Test suite times"
  echo
  echo "Written by \`bash scripts/suite-times.sh\` on $(nproc) cores ($(date -u +%Y-%m-%d)); wall seconds per part,"
  echo "each part one process. The fast part is \`cargo test --release --lib --bins --test it\`; the"
  echo "heavy replays \`cargo test --release --test replays\` (a CI step of their own)."
  echo
  echo "| part | tests | seconds |"
  echo "|---|---:|---:|"
  printf '%s' "$rows"
  echo
  printf 'Build of every test binary (incremental, after the last change): %.0f s. ' "$build_s"
  printf 'Fast part: %.0f s. Heavy replays: %.0f s.\n' "$fast_s" "$heavy_s"
} >"$out"
echo "wrote $out"
exit "$failed"
