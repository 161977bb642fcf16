#!/usr/bin/env bash
# Installs the Python module built in build/python for the interpreter the build found (the one
# with numpy, see python/CMakeLists.txt), as an editable install (like `pip install -e`): a
# kontur.pth file in that interpreter's per-user site-packages (inside a virtual environment: its
# site-packages) puts build/python on its path, so a rebuild updates the module. To uninstall,
# delete the kontur.pth file this prints.
set -euo pipefail
cd "$(dirname "$0")/.."
package_dir="$(pwd)/build/python"
if [ ! -f build/CMakeCache.txt ] || [ ! -d "$package_dir/kontur" ]; then
  echo "install-python: build/python/kontur is missing: run scripts/build.sh first" >&2
  exit 1
fi
py="$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' build/CMakeCache.txt)"
if [ -z "$py" ]; then
  echo "install-python: the build found no Python (see the warning of cmake); nothing installed" >&2
  exit 1
fi
site="$("$py" - <<'PY'
import site, sys, sysconfig
in_venv = sys.prefix != getattr(sys, "base_prefix", sys.prefix)
print(sysconfig.get_paths()["purelib"] if in_venv or not site.ENABLE_USER_SITE else site.getusersitepackages())
PY
)"
mkdir -p "$site"
echo "$package_dir" > "$site/kontur.pth.tmp"
mv "$site/kontur.pth.tmp" "$site/kontur.pth"
version="$(cd / && "$py" -c 'import kontur; print(kontur.__version__)')"
echo "install-python: kontur $version for $py ($site/kontur.pth -> $package_dir)"
# The python3 a user types may be another interpreter (e.g. a pyenv one first on PATH).
if command -v python3 >/dev/null 2>&1 && [ "$(command -v python3)" != "$py" ]; then
  if (cd / && python3 -c 'import kontur, numpy' >/dev/null 2>&1); then
    echo "install-python: python3 on PATH ($(command -v python3)) imports it too"
  else
    echo "install-python: note: python3 on PATH ($(command -v python3)) is another interpreter; use $py" \
         "(or install numpy and point that one at $package_dir)"
  fi
fi
