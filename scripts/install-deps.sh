#!/usr/bin/env bash
# Installs the Debian packages Kontur needs to build, test and benchmark. Idempotent: packages
# already installed are not touched; apt-get runs only when something is missing.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libfmt-dev nlohmann-json3-dev libtomlplusplus-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libtbb-dev  # OpenCASCADE's CMake targets name libtbb.so, which only the -dev package installs
  clang libclang-rt-14-dev  # the libFuzzer target of the G-code reader (fuzz/, docs/gcode.md)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} Debian packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
