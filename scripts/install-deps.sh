#!/usr/bin/env bash
# Installs the Debian packages Kontur needs to build, test and benchmark, and the npm packages of
# the HTML report (plotly.js, embedded at build time; playwright-core for the browser test, which
# drives Debian's chromium). Idempotent: packages already installed are not touched; apt-get runs
# only when something is missing, `npm ci` only when node_modules does not match package-lock.json.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libcli11-dev libfmt-dev nlohmann-json3-dev libtomlplusplus-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libtbb-dev  # OpenCASCADE's CMake targets name libtbb.so, which only the -dev package installs
  clang libclang-rt-14-dev  # the libFuzzer target of the G-code reader (fuzz/, docs/gcode.md)
  chromium    # the browser test of the HTML report (tests/browser), /usr/bin/chromium
  gcc-arm-none-eabi  # the lower level's build for a Cortex-M4 (lower_level/build_cortex_m4.sh, a test)
  # The Python module (python/, docs/python.md): Debian's Python 3 with its headers, pybind11,
  # numpy for the arrays, pytest for its tests, matplotlib for the example (examples/python/).
  python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib
)
# Node.js and npm: Debian's packages, unless a node and an npm are already there (a Node.js from
# another source ships its own npm, which Debian's npm package would conflict with).
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} Debian packages present"
else
  echo "install-deps: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm packages, exactly as pinned in package-lock.json. npm ci removes and reinstalls
# node_modules, so it runs only when an installed package is missing or of another version.
npm_current() {
  node -e '
    const fs = require("fs");
    const lock = JSON.parse(fs.readFileSync("package-lock.json", "utf8"));
    for (const [path, info] of Object.entries(lock.packages)) {
      if (!path) continue;
      const file = path + "/package.json";
      if (!fs.existsSync(file) || JSON.parse(fs.readFileSync(file, "utf8")).version !== info.version) process.exit(1);
    }' 2>/dev/null
}
if npm_current; then
  echo "install-deps: npm packages present (as in package-lock.json)"
else
  echo "install-deps: npm ci"
  npm ci --no-audit --no-fund --loglevel=error
fi
