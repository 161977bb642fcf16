#!/usr/bin/env bash
# Opt-in stress run: every readable program of ../shared/data/gcode and of tests/data/corpus (in
# its dialect, from expected.tsv) on every machine of ../shared/data/gcode/linuxcnc-tp/configs and
# examples/machines, through `kontur run` (setpoints checked, none written). Prints one line per run
# that is not a pass or a refusal with a message (exit 4: a limit exceeded; a crash; a timeout),
# then a table of outcomes per machine; exits 1 when a run exceeded a limit or crashed.
#
#   tests/stress/machine_sweep.sh [KONTUR] [TIMEOUT_S] [JOBS]
#
# KONTUR defaults to build/bin/kontur, TIMEOUT_S to 60 (a timeout is listed, not failed: a program
# whose axis is slow on a machine can take hours of machining), JOBS to the number of cores.
# SWEEP_FILTER (an extended regex) keeps only the programs whose path matches it.
# 2026-12-04 it found: a flat helix on XY_slowZ.ini at 1.10 times X's acceleration, paths along an
# axis XY.ini / XZ.ini lack running as jumps, and a jerk of 1.005 times the limit on XYZ_medium.ini.
set -uo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
kontur="$(realpath "${1:-$root/build/bin/kontur}")"
timeout_s="${2:-60}"
jobs="${3:-$(nproc)}"
shared="$root/../shared/data/gcode"
[ -x "$kontur" ] || { echo "machine_sweep: $kontur is not an executable (build first: scripts/build.sh)" >&2; exit 2; }
[ -d "$shared" ] || { echo "machine_sweep: $shared is missing (../shared beside the checkout)" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# program<TAB>dialect (empty: detected)
{
  find "$shared" -name '*.ngc' | LC_ALL=C sort | sed 's/$/\t/'
  awk -F'\t' -v dir="$root/tests/data/corpus/" 'NR > 1 && $3 !~ /^(invalid|refuse)/ { print dir $1 "\t" $2 }' \
    "$root/tests/data/corpus/expected.tsv"
} | grep -E -- "${SWEEP_FILTER:-.}" > "$work/programs.tsv"
find "$shared/linuxcnc-tp/configs" "$root/examples/machines" -name '*.ini' -o -name '*.toml' | LC_ALL=C sort > "$work/machines.txt"
while read -r m; do sed "s|^|$m\t|" "$work/programs.tsv"; done < "$work/machines.txt" > "$work/jobs.tsv"

# One run: machine<TAB>program<TAB>dialect -> "machine program outcome detail"
run_one() {
  local m="$1" p="$2" d="$3" out rc
  out="$(mktemp -d)"
  timeout "$timeout_s" "$kontur" run "$p" ${d:+--dialect "$d"} --machine "$m" --json --quiet \
    > "$out/s.json" 2> "$out/err.txt"
  rc=$?
  local kind
  case $rc in
    0) kind=pass ;;
    1) if [ -s "$out/err.txt" ]; then kind=refused; else kind=crash; fi ;;
    4) kind=violation ;;
    124) kind=timeout ;;
    *) kind=crash ;;
  esac
  local detail=""
  if [ "$kind" = violation ] || [ "$kind" = crash ]; then
    detail="$(/usr/bin/python3 -c 'import json,sys
try:
    d = json.load(open(sys.argv[1])); print("; ".join(d.get("failures", []))[:200])
except Exception:
    print(open(sys.argv[2]).read().strip()[:200])' "$out/s.json" "$out/err.txt")"
  fi
  local shown="${p#"$root"/../}"
  printf '%s\t%s\t%s\t%s\n' "$(basename "$m")" "${shown#"$root"/}" "$kind" "$detail"
  rm -rf "$out"
}
export -f run_one
export kontur timeout_s root

tr '\t' '\n' < "$work/jobs.tsv" | xargs -d '\n' -n 3 -P "$jobs" bash -c 'run_one "$0" "$1" "$2"' > "$work/results.tsv"

awk -F'\t' '$3 != "pass" && $3 != "refused" { print $1 "  " $2 "  " $3 "  " $4 }' "$work/results.tsv" | LC_ALL=C sort
echo
awk -F'\t' '{ n[$1]++; k[$1 " " $3]++; m[$1] = 1 }
  END {
    printf "%-42s %6s %6s %8s %9s %7s %6s\n", "machine", "runs", "pass", "refused", "violation", "timeout", "crash"
    for (x in m) printf "%-42s %6d %6d %8d %9d %7d %6d\n", x, n[x], k[x " pass"], k[x " refused"], k[x " violation"], k[x " timeout"], k[x " crash"]
  }' "$work/results.tsv" | { read -r head; echo "$head"; LC_ALL=C sort; }
bad=$(awk -F'\t' '$3 == "violation" || $3 == "crash"' "$work/results.tsv" | wc -l)
echo "machine_sweep: $(wc -l < "$work/results.tsv") runs, $bad violations or crashes"
[ "$bad" -eq 0 ]
