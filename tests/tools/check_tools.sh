#!/bin/sh
# Fails, with what to install, where a tool the tests need is missing or older than the project
# needs: Node.js (the version playwright-core and package.json's "engines" ask for), the npm
# packages pinned in package-lock.json, and Debian's Chromium for the browser test of the report.
# Runs in the repository root:   sh tests/tools/check_tools.sh
# POSIX sh, and no newer Node than the one it checks: it must speak where the tools are old.
# KONTUR_NODE names the node the browser test runs (default: node on PATH).
set -u
node="${KONTUR_NODE:-node}"
failed=0
fail() { echo "check_tools: $*"; failed=1; }

# The major version in an "engines": {"node": ">=N..."} field of a package.json (empty if none).
required_node_major() {
  sed -n '/"engines"/,/}/p' "$1" | sed -n 's/.*"node" *: *"[^0-9]*\([0-9][0-9]*\).*/\1/p' | head -n 1
}

if ! command -v "$node" >/dev/null 2>&1; then
  fail "node is missing: run scripts/install-deps.sh (Debian 12: apt-get install nodejs npm)"
else
  node_version="$("$node" --version | sed 's/^v//')"
  node_major="${node_version%%.*}"
  for pkg in package.json node_modules/playwright-core/package.json; do
    [ -f "$pkg" ] || continue
    need="$(required_node_major "$pkg")"
    if [ -n "$need" ] && [ "$node_major" -lt "$need" ]; then
      fail "node $node_version is older than the $need that $pkg needs: install Node.js $need or newer" \
           "(Debian 12's nodejs is 18), or pin a version of that package that runs on node $node_major"
    fi
  done
  echo "check_tools: node $node_version"
fi

# Every npm package at the version package-lock.json pins (npm ci installs exactly those).
if [ -f package-lock.json ] && command -v "$node" >/dev/null 2>&1; then
  stale="$("$node" -e '
    const fs = require("fs");
    const lock = JSON.parse(fs.readFileSync("package-lock.json", "utf8"));
    for (const [path, info] of Object.entries(lock.packages)) {
      if (!path) continue;
      const file = path + "/package.json";
      const have = fs.existsSync(file) ? JSON.parse(fs.readFileSync(file, "utf8")).version : "none";
      if (have !== info.version) console.log(path + " is " + have + ", package-lock.json pins " + info.version);
    }' 2>&1)"
  if [ -n "$stale" ]; then
    fail "npm packages differ from package-lock.json: run scripts/install-deps.sh (npm ci):"
    echo "$stale" | sed 's/^/  /'
  fi
fi

chromium="${KONTUR_CHROMIUM:-/usr/bin/chromium}"
if [ ! -x "$chromium" ]; then
  fail "$chromium is missing: run scripts/install-deps.sh (Debian: apt-get install chromium)"
elif ! chromium_version="$("$chromium" --version 2>/dev/null)"; then
  fail "$chromium does not start: reinstall it (apt-get install --reinstall chromium)"
else
  echo "check_tools: $chromium_version"
fi

if [ "$failed" -ne 0 ]; then exit 1; fi
echo "check_tools: every tool the tests need is present and new enough"
