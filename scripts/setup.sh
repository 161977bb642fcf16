#!/usr/bin/env bash
# Quick start, first command: installs the Debian and npm packages, builds what Kontur's main job
# needs (the library with the report, the command, the Python module; the tests, benchmarks and
# fuzzer are built by scripts/test.sh), installs `import kontur` (scripts/install-python.sh), and
# runs the main job on a bundled example: the part program examples/programs/square_arc.ngc
# planned on the default machine, with its setpoints, JSON summary and report in build/. It ends
# with the run's short summary and where the report is.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
scripts/install-deps.sh
scripts/build.sh kontur_app kontur_python
echo
scripts/install-python.sh
py="$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)"
if [ -n "$py" ]; then
  echo "== $py -c 'import kontur; print(kontur.run(\"examples/programs/square_arc.ngc\"))'"
  "$py" -c 'import kontur; print(kontur.run("examples/programs/square_arc.ngc"))'
fi
echo
echo "== kontur spline examples/curves/seed_example1.json --step 0.05 --report build/seed_example1.html"
build/bin/kontur spline examples/curves/seed_example1.json --step 0.05 --report build/seed_example1.html \
    > build/seed_example1.txt
echo "   the seed's example curve: span polynomials, lengths, forward differences in build/seed_example1.txt"
echo
echo "== kontur run examples/programs/square_arc.ngc -o build/square_arc.csv --summary build/square_arc.json --report build/square_arc.html"
build/bin/kontur run examples/programs/square_arc.ngc -o build/square_arc.csv --summary build/square_arc.json \
    --report build/square_arc.html
echo
echo "Set up in $(( $(date +%s) - start )) s. Open the report in a browser (one file, no network needed):"
echo "  xdg-open build/square_arc.html      (and build/seed_example1.html)"
echo "All tests: scripts/test.sh"
