#!/usr/bin/env bash
# Issue 17's targets for `kontur compress`: per shared CAM program at a tolerance, the feed blocks
# before and after, the largest deviation both ways (the compressor's own check of the written
# program), the compression speed, and the machining time `kontur run` plans for the original and
# the compressed program on LinuxCNC's XYZ.ini (each run also checked by the planner's checker).
#   bench/compress_runs.sh KONTUR_BINARY SHARED_DIR [TOLERANCE_MM] [OUT_DIR]
# Two compressed versions: the dialect's default curves (LinuxCNC: arcs and G6.2 splines) and
# arcs only (what LinuxCNC 2.9 reads: the peer's version). OUT_DIR keeps the programs, e.g. for
# ../shared/tools/linuxcnc-peer/lcnc_run.py. random_lines is run with G20 prepended (LinuxCNC reads
# it in its INI's inches).
set -euo pipefail
kontur="$(realpath "$1")"
gcode="$(realpath "$2")/data/gcode"
tol="${3:-0.01}"
out="${4:-$(mktemp -d)}"
mkdir -p "$out"
ini="$gcode/linuxcnc-tp/configs/XYZ.ini"
programs=(3D_Chips.ngc linuxcnc-tp/performance/3D_Chips.ngc linuxcnc-tp/performance/circle_small_segments_ncd.ngc
          linuxcnc-tp/performance/random_lines_0.001in.ngc linuxcnc-tp/performance/short_segments_0.001.ngc)
printf '| program | feed blocks | compressed (arcs+splines) | ratio | arcs only | ratio | deviation [mm] | input blocks/s | kontur run [s] original | compressed | arcs only | time ratio |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|\n'
for p in "${programs[@]}"; do
  key="$(echo "$p" | tr '/' '_')"
  src="$gcode/$p"
  if [[ "$p" == *random_lines* ]]; then { echo "G20"; cat "$src"; } >"$out/$key"; src="$out/$key"; fi
  cp "$src" "$out/orig_$key"
  "$kontur" compress "$out/orig_$key" -o "$out/c_$key" --tolerance "$tol" --dialect linuxcnc --report "$out/c_$key.json" >"$out/c_$key.txt"
  "$kontur" compress "$out/orig_$key" -o "$out/a_$key" --tolerance "$tol" --dialect linuxcnc --curves arcs --report "$out/a_$key.json" >/dev/null
  for v in orig c a; do
    "$kontur" run "$out/${v}_$key" --machine "$ini" -o "$out/${v}_$key.bin" --format binary \
        --summary "$out/${v}_$key.run.json" --quiet || echo "run of ${v}_$key: exit $?" >&2
  done
  /usr/bin/python3 - "$out" "$key" "$p" <<'PY'
import json, re, sys
out, key, name = sys.argv[1:]
c = json.load(open(f"{out}/c_{key}.json")); a = json.load(open(f"{out}/a_{key}.json"))
speed = re.search(r"\(([0-9]+) input blocks/s\)", open(f"{out}/c_{key}.txt").read()).group(1)
t = {v: json.load(open(f"{out}/{v}_{key}.run.json")) for v in ("orig", "c", "a")}
ok = all(x["passed"] for x in t.values())
print(f"| {name} | {c['feed_blocks_in']} | {c['feed_blocks_out']} | {c['ratio']:.2f} | {a['feed_blocks_out']} | {a['ratio']:.2f} "
      f"| {max(c['max_deviation_mm'], a['max_deviation_mm']):.4f} | {speed} | {t['orig']['total_time_s']:.3f} "
      f"| {t['c']['total_time_s']:.3f} | {t['a']['total_time_s']:.3f} | {t['c']['total_time_s'] / t['orig']['total_time_s']:.3f}"
      f"{'' if ok else ' (a run failed its check)'} |")
PY
done
echo "programs in $out"
