#!/usr/bin/env bash
# Set up what the tests need (the app, pytest, ROS 2's rclpy for the differential suite, Playwright,
# Debian's Chromium, bubblewrap and docker-compose, the linters, the page's scripts) and run the
# check gate (scripts/check: ruff, ruff format, mypy --strict, tsc, eslint, then the whole suite).
# Extra arguments go to pytest. CI runs exactly this (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/_venv.sh
source scripts/_web.sh
source scripts/_oracle.sh
install_once '.[test]'
# ROS 2's own rclpy, the differential suite's reference (tests/differential), in a venv of its own.
oracle_install

debian_tool() {  # COMMAND PACKAGE FOR-WHAT IF-NOT: Debian's PACKAGE where COMMAND is missing (root with apt)
  if command -v "$1" >/dev/null 2>&1; then
    return
  fi
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "Installing Debian's $2 $3 ..."
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq "$2" >/dev/null
  else
    echo "No $1 on PATH: $4 (install Debian's '$2')." >&2
  fi
}

debian_tool chromium chromium "for the browser tests" "the browser tests will be skipped"
# bubblewrap: a class server's students' nodes run in its sandbox (tests/sandbox proves what it blocks).
debian_tool bwrap bubblewrap "for students' nodes on a class server" \
  "a class server will refuse students' nodes and the sandbox tests will be skipped"
# docker-compose resolves docker-compose.yml without a container engine (tests/test_container_files.py).
debian_tool docker-compose docker-compose "to check docker-compose.yml" "the compose file's check will be skipped"

# pytest rewrites the asserts of each test module it imports and keeps the result beside the
# bytecode below; the gate's first part then starts its workers at once, and on a fresh clone each
# one rewrote every module itself (a collection took 16 CPU-s cold against 8 warm, five at once 79
# against 43). One collection fills that cache now, beside the page's build. Its verdict is the
# gate's to give: a module that fails to import fails there.
PYCACHE="$(cd "$VENV" && pwd)/pycache"
env -u PYTHONDONTWRITEBYTECODE PYTHONPYCACHEPREFIX="$PYCACHE" "$VENV/bin/python" -m pytest --collect-only -q \
  -p no:xdist -p no:cacheprovider tests >/dev/null 2>&1 &
REWRITE_PID=$!

# The page's scripts (web/ → static/build), with Node from the machine or from PyPI; the same
# npm then installs roslib for the rosbridge client test (tests/js, pinned by its lock file).
web_build
npm ci --prefix tests/js --no-audit --no-fund --loglevel=error >/dev/null

# pip compiled the packages' bytecode beside them, but scripts/check has Python keep bytecode in
# $VENV/pycache (PYTHONPYCACHEPREFIX), where it looks for nothing else: compile everything there
# once now, as pip does at install, rather than in each of the gate's first processes at once.
# (A file or two of the packages' own that is not Python 3 makes compileall exit non-zero.)
env -u PYTHONDONTWRITEBYTECODE PYTHONPYCACHEPREFIX="$PYCACHE" "$VENV/bin/python" -m compileall \
  -q -j0 "$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')" \
  server api sim client node_runtime tests >/dev/null || true
wait "$REWRITE_PID" || true

exec env TELEOP_VENV="$VENV" bash scripts/check "$@"
