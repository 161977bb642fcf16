#!/usr/bin/env bash
# Quick start, first command: installs the Debian and npm packages, builds Kontur and runs its main
# job on a bundled example: the part program examples/programs/square_arc.ngc planned on the
# default machine (setpoints, summary and report in build/), and the report of the seed's example curve;
# installs the Python module for the interpreter the build found (scripts/install-python.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
echo
echo "== kontur run examples/programs/square_arc.ngc -o build/square_arc.csv --summary build/square_arc.json --report build/square_arc.html"
build/bin/kontur run examples/programs/square_arc.ngc -o build/square_arc.csv --summary build/square_arc.json \
    --report build/square_arc.html
cat build/square_arc.json
echo
echo "== kontur spline examples/curves/seed_example1.json --step 0.05 --report build/seed_example1.html"
build/bin/kontur spline examples/curves/seed_example1.json --step 0.05 --report build/seed_example1.html
echo
scripts/install-python.sh
py="$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)"
echo "== $py -c 'import kontur; print(kontur.run(\"examples/programs/square_arc.ngc\"))'"
"$py" -c 'import kontur; print(kontur.run("examples/programs/square_arc.ngc"))'
echo
echo "Open the reports in a browser (no network needed), e.g.: xdg-open build/square_arc.html"
echo "  (and build/seed_example1.html)"
