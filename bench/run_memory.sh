#!/usr/bin/env bash
# Peak memory of `kontur run` against the number of setpoints (issue 19): the shared 3D_Chips.ngc
# (4,795 moves) at servo periods of 1 ms, 100 us and 10 us (about 10^5, 10^6 and 10^7 setpoints),
# without -o and writing binary setpoints, then any PROGRAM given (e.g. CAMotics' examples/tiger/tiger.nc,
# 17 million setpoints at 1 ms). Peak = the maximum resident set size from GNU time.
#
#   bench/run_memory.sh [BUILD_DIR] [PROGRAM ...]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"; shift || true
kontur="$build/bin/kontur"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
chips=../shared/data/gcode/3D_Chips.ngc
printf '| program | servo period | setpoints | moves | output | peak memory [MB] | wall time [s] | exit |\n|---|---|---|---|---|---|---|---|\n'
measure() {  # program period output
  local program="$1" period="$2" output="$3" args=()
  printf 'servo_period_s = %s\n' "$period" > "$work/machine.toml"
  [ "$output" = binary ] && args=(-o "$work/setpoints.bin" --format binary)
  local rc=0
  /usr/bin/time -f '%M %e' -o "$work/time" "$kontur" run "$program" --machine "$work/machine.toml" "${args[@]}" \
      --summary "$work/summary.json" --quiet || rc=$?
  read -r kb seconds < <(tail -n 1 "$work/time")  # (GNU time puts a line on a non-zero exit first)
  local n moves
  n=$(sed -n 's/^  "setpoints": \([0-9]*\),/\1/p' "$work/summary.json")
  moves=$(sed -n 's/^  "moves": \([0-9]*\),/\1/p' "$work/summary.json")
  printf '| %s | %s s | %s | %s | %s | %s | %s | %s |\n' "$(basename "$program")" "$period" "$n" "$moves" "$output" \
      "$(awk -v kb="$kb" 'BEGIN { printf "%.1f", kb / 1024 }')" "$seconds" "$rc"
  rm -f "$work/setpoints.bin"
}
for period in 0.001 0.0001 0.00001; do
  measure "$chips" "$period" none
  measure "$chips" "$period" binary
done
for program in "$@"; do
  measure "$program" 0.001 none
  measure "$program" 0.001 binary
done
