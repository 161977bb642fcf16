#!/usr/bin/env bash
# Configures and builds Kontur in build/ (Release): everything, or only the targets given
# (scripts/setup.sh builds kontur_app and kontur_python). In CI (CI=true) warnings are errors.
set -euo pipefail
cd "$(dirname "$0")/.."
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DKONTUR_WERROR=${werror} >/dev/null
if [ $# -gt 0 ]; then
  targets=()
  for t in "$@"; do
    # (kontur_python exists only where cmake found a Python for it; its warning said why not)
    if [ "$t" = kontur_python ] && [[ "$(cmake --build build --target help 2>/dev/null)" != *kontur_python* ]]; then
      continue
    fi
    targets+=(--target "$t")
  done
  cmake --build build -j"$(nproc)" "${targets[@]}"
else
  cmake --build build -j"$(nproc)"
fi
