#!/usr/bin/env bash
# Builds the lower level (kontur_ll.c) for a Cortex-M4F microcontroller with Debian's
# gcc-arm-none-eabi, freestanding, and reports its code and RAM size:
#   lower_level/build_cortex_m4.sh [OUT_DIR]
# Fails when the object needs anything but libgcc's floating-point helpers (__aeabi_*): no heap,
# no libm, no standard I/O, no memcpy/memset. Exit 77 (skipped) when arm-none-eabi-gcc is missing
# (scripts/install-deps.sh installs it).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:-$(mktemp -d)}"
mkdir -p "$out"
cc="${ARM_CC:-arm-none-eabi-gcc}"
if ! command -v "$cc" >/dev/null 2>&1; then
  echo "SKIP: $cc not found (scripts/install-deps.sh installs gcc-arm-none-eabi)"
  exit 77
fi
prefix="${cc%gcc}"
# -fno-tree-loop-distribute-patterns: GCC would otherwise turn the zeroing loops into memset calls.
flags=(-std=c99 -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -ffreestanding -fno-builtin
       -fno-tree-loop-distribute-patterns -ffp-contract=off -Os -fstack-usage
       -Wall -Wextra -Wpedantic -Wconversion -Wshadow -Werror)
"$cc" "${flags[@]}" -c "$here/kontur_ll.c" -o "$out/kontur_ll.o"
# The state a controller keeps: one kll_stream.
printf '#include "kontur_ll.h"\nkll_stream kontur_ll_state;\n' >"$out/state.c"
"$cc" "${flags[@]}" -I "$here" -c "$out/state.c" -o "$out/state.o"

undefined="$("${prefix}nm" -u "$out/kontur_ll.o" | awk '{print $2}')"
bad="$(echo "$undefined" | grep -v -E '^(__aeabi_[a-z0-9]+)?$' || true)"
if [ -n "$bad" ]; then
  echo "FAIL: kontur_ll.o needs more than libgcc's floating-point helpers:"
  echo "$bad"
  exit 1
fi
read -r text data bss _ < <("${prefix}size" "$out/kontur_ll.o" | tail -1)
state_hex="$("${prefix}nm" -S "$out/state.o" | awk '$4 == "kontur_ll_state" {print $2}')"
state=$((16#$state_hex))
stack="$(sort -t$'\t' -k2 -n "$out/kontur_ll.su" | awk -F'\t' '{print $2 " (" $1 ")"}' | tail -1)"
echo "cortex-m4: code ${text} bytes, data ${data} bytes, bss ${bss} bytes (flash: code + data)"
echo "cortex-m4: state (one kll_stream, RAM) ${state} bytes; deepest stack frame ${stack}"
echo "cortex-m4: libgcc helpers used: $(echo $undefined | tr '\n' ' ')"
