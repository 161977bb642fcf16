#!/usr/bin/env bash
# Quick start, first command: installs the Debian packages, builds Kontur and runs its main job
# on a bundled example.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
echo
echo "== kontur spline examples/curves/seed_example1.json --step 0.05"
build/bin/kontur spline examples/curves/seed_example1.json --step 0.05
