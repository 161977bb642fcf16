#!/usr/bin/env bash
# Issue 16's size target: the segment stream of every shared program against its binary
# setpoints (48 bytes per setpoint for X Y Z), at the machine's servo period of 1 ms and at 125 us,
# on LinuxCNC's XYZ.ini. Each stream is also replayed (kontur replay) and checked (kontur verify).
#   bench/segment_sizes.sh KONTUR_BINARY SHARED_DIR [TOLERANCE_MM]
# Prints one row per program and period: setpoints, pieces, stream bytes, bytes per second of
# motion, size ratio (binary / stream), largest replay error, verify's verdict; then the smallest
# ratio per period.
set -euo pipefail
kontur="$(realpath "$1")"
gcode="$(realpath "$2")/data/gcode"
tol="${3:-1e-6}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
ini="$gcode/linuxcnc-tp/configs/XYZ.ini"
"$kontur" machine "$ini" | sed 's/^servo_period_s = .*/servo_period_s = 0.000125/' >"$work/xyz_125us.toml"
row() {  # program period-label machine
  local p="$1" label="$2" machine="$3" key; key="$(echo "$p $label" | tr '/ ' '__')"
  local rc=0
  "$kontur" run "$gcode/$p" --machine "$machine" --format segments --segment-tolerance "$tol" \
      -o "$work/$key.seg" --summary "$work/$key.json" --quiet 2>/dev/null || rc=$?
  if [ ! -f "$work/$key.json" ]; then echo "$p $label run-exit=$rc"; return; fi
  local verdict=-
  if [ -f "$work/$key.seg" ]; then
    "$kontur" replay "$work/$key.seg" -o "$work/$key.bin" --format binary --quiet
    verdict=fail
    "$kontur" verify "$gcode/$p" "$work/$key.bin" --machine "$machine" --quiet --summary "$work/$key.v.json" && verdict=pass
  fi
  /usr/bin/python3 - "$work/$key.json" "$p" "$label" "$verdict" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); s = d["segments"]
if d["setpoints"] == 0:
    print(f'{sys.argv[2]} {sys.argv[3]} no motion'); sys.exit(0)
print(f'{sys.argv[2]} {sys.argv[3]} setpoints={d["setpoints"]} pieces={s["pieces"]} bytes={s["bytes"]} '
      f'bytes_per_s={s["bytes_per_second"]:.0f} ratio={s["size_ratio_to_binary"]:.2f} '
      f'max_error_mm={s["max_error_mm"]:.3g} replay_verify={sys.argv[4]}')
PY
  rm -f "$work/$key".*
}
export -f row
export kontur gcode tol work
cd "$gcode"
find . -name '*.ngc' | sed 's|^\./||' | LC_ALL=C sort | while read -r p; do
  echo "$p 1ms $ini"
  echo "$p 125us $work/xyz_125us.toml"
done | xargs -P "$(nproc)" -L 1 bash -c 'row "$@"' _ | LC_ALL=C sort >"$work/rows"
cat "$work/rows"
for label in 1ms 125us; do
  grep " $label " "$work/rows" | grep -o 'ratio=[0-9.]*' | cut -d= -f2 | sort -g | head -1 |
    xargs -I{} echo "smallest ratio at $label: {}"
  echo "replays failing verify at $label: $(grep " $label " "$work/rows" | grep -c 'replay_verify=fail' || true)"
done
