# Sourced by .ci/run and scripts/test.sh: `step NAME COMMAND…` runs COMMAND, prints its wall
# time as "step NAME: S s", and appends "NAME<TAB>S<TAB>status" to $COVGA_STEP_LOG when that is
# set (scripts/suite-times.sh reads it). A failing step stops the script with its exit status.

step() {
  local name="$1" start end secs rc
  shift
  echo "::: step $name: $*"
  start=$(date +%s.%N)
  if "$@"; then rc=0; else rc=$?; fi
  end=$(date +%s.%N)
  secs=$(awk "BEGIN { printf \"%.1f\", $end - $start }")
  echo "::: step $name: ${secs} s$([ "$rc" = 0 ] || echo " (failed, exit $rc)")"
  if [ -n "${COVGA_STEP_LOG:-}" ]; then
    printf '%s\t%s\t%s\n' "$name" "$secs" "$([ "$rc" = 0 ] && echo ok || echo "exit $rc")" >>"$COVGA_STEP_LOG"
  fi
  return "$rc"
}
