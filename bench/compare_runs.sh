#!/usr/bin/env bash
# Two builds of kontur on every shared program, in one script (the baseline in the same run, as
# every speed claim needs): the planned machining time of each, the time ratio to the time-optimal
# reference, and whether the independent check passed. Prints the programs whose time changed
# (before, after, after / before), then how many got faster and slower, the geometric mean of the
# changes, how many runs are within 1.10 of the reference before and after, and every run whose
# check result or refusal changed. Exits 1 where a run that passed before fails after.
#
#   bench/compare_runs.sh BEFORE AFTER [MACHINE] [JOBS]
#
# BEFORE, AFTER: kontur binaries (e.g. a copy of build/bin/kontur made before a change).
# MACHINE defaults to LinuxCNC's XYZ.ini of the shared data; examples/machines/*.toml work too
# (issue 12's jerk = A / T machine: examples/machines/linuxcnc_xyz_acceleration_limited.toml).
# JOBS defaults to the number of cores. SHARED (default ../shared beside the checkout) and FILTER
# (an extended regex on the program's path) may be set in the environment. Each run has 120 s.
# Nothing is written but the report: `kontur run` without -o writes no setpoints.
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [[ $# -lt 2 ]]; then
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
before="$(realpath "$1")"
after="$(realpath "$2")"
shared="$(realpath "${SHARED:-$root/../shared}")/data/gcode"
machine="$(realpath "${3:-$shared/linuxcnc-tp/configs/XYZ.ini}")"
jobs="${4:-$(nproc)}"
for f in "$before" "$after" "$machine"; do
  [[ -f "$f" ]] || { echo "compare_runs: no such file: $f" >&2; exit 2; }
done
[[ -d "$shared" ]] || { echo "compare_runs: no shared programs at $shared" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# one line per program and build: path, total time [s], time ratio, passed (or "refused")
run_one() {
  local bin="$1" program="$2"
  local out
  if out="$(timeout 120 "$bin" run "$program" --machine "$machine" --json --quiet --time-optimal 2>/dev/null)" ||
     [[ -n "$out" ]]; then
    printf '%s' "$out" | python3 -c '
import json, sys
try:
    d = json.load(sys.stdin)
    r = d.get("time_ratio")
    print(d["total_time_s"], "-" if r is None else r, "passed" if d["passed"] else "failed")
except Exception:
    print("- - refused")'
  else
    echo "- - refused"
  fi
}
export -f run_one
export machine

(cd "$shared" && find . -name '*.ngc' | sort | grep -E "${FILTER:-.}") >"$work/programs"
for side in before after; do
  bin="$before"; [[ "$side" == after ]] && bin="$after"
  (cd "$shared" && xargs -P "$jobs" -I{} bash -c 'echo "{} $(run_one "$0" "{}")"' "$bin" <"$work/programs") |
    sort >"$work/$side"
done
python3 - "$work/before" "$work/after" <<'PY'
import math, sys

def load(path):
    runs = {}
    for line in open(path):
        p = line.split()
        if len(p) == 4:
            runs[p[0]] = p[1:]
    return runs

a, b = load(sys.argv[1]), load(sys.argv[2])
faster = slower = 0
logs = []
broke = False
print(f"{'program':72s} {'before [s]':>11s} {'after [s]':>11s} {'after/before':>12s}")
for k in sorted(a):
    x, y = a[k], b.get(k, ["-", "-", "refused"])
    if x[2] != y[2]:
        print(f"{k:72s} check: {x[2]} -> {y[2]}")
        broke = broke or (x[2] == "passed" and y[2] != "passed")
    if x[0] == "-" or y[0] == "-":
        continue
    tx, ty = float(x[0]), float(y[0])
    if tx > 0 and ty > 0:
        logs.append(math.log(ty / tx))
    if abs(ty - tx) > 1e-9 * max(1.0, tx):
        faster += ty < tx
        slower += ty > tx
        print(f"{k:72s} {tx:11.3f} {ty:11.3f} {ty / tx:12.4f}")
within = lambda runs: sum(1 for r in runs.values() if r[1] not in ("-", "None") and float(r[1]) <= 1.10)
ratios = lambda runs: sum(1 for r in runs.values() if r[1] not in ("-", "None"))
gm = math.exp(sum(logs) / len(logs)) if logs else 1.0
print(f"faster {faster}, slower {slower}, unchanged {len(logs) - faster - slower}; "
      f"geometric mean after / before {gm:.5f} over {len(logs)} runs")
print(f"within 1.10 of the time-optimal reference: before {within(a)} of {ratios(a)}, after {within(b)} of {ratios(b)}")
sys.exit(1 if broke else 0)
PY
