#!/usr/bin/env bash
# Quick start, second command: installs what is missing, builds, and runs every test (ctest).
# KONTUR_TEST_COUNT and KONTUR_TEST_SEED scale the seeded random tests (see README).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
