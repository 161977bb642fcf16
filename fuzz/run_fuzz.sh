#!/usr/bin/env bash
# Runs the G-code reader's libFuzzer target. Usage:
#   fuzz/run_fuzz.sh FUZZER SECONDS WORK_CORPUS_DIR [SEED_DIR...]
# Exit 77 (ctest: skipped) if FUZZER was not built (no clang / libFuzzer runtime on this machine).
set -uo pipefail
fuzzer=$1 seconds=$2 corpus=$3
shift 3
if [ ! -x "$fuzzer" ]; then
  echo "fuzz: skipped: $fuzzer was not built (clang with libFuzzer not found: install clang and libclang-rt-14-dev," \
       "scripts/install-deps.sh does, then reconfigure)"
  exit 77
fi
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$corpus"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
exec "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 -print_final_stats=1 \
  -dict="$here/gcode.dict" "$corpus" "$@"
