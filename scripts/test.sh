#!/usr/bin/env bash
# Set up what the tests need (the app, pytest, Playwright, Debian's Chromium, the linters, the page's
# scripts) and run the check gate (scripts/check: ruff, ruff format, mypy --strict, tsc, eslint,
# then the whole suite). Extra arguments go to pytest. CI runs exactly this (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/_venv.sh
source scripts/_web.sh
install_once '.[test]'

if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "Installing Debian's chromium for the browser tests ..."
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq chromium >/dev/null
  else
    echo "No chromium on PATH: the browser tests will be skipped (install Debian's 'chromium' to run them)." >&2
  fi
fi

# bubblewrap: a class server's students' nodes run in its sandbox (tests/sandbox proves what it blocks).
if ! command -v bwrap >/dev/null 2>&1; then
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "Installing Debian's bubblewrap for students' nodes on a class server ..."
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq bubblewrap >/dev/null
  else
    echo "No bwrap on PATH: a class server will refuse students' nodes and the sandbox tests will be skipped (install Debian's 'bubblewrap')." >&2
  fi
fi

# The page's scripts (web/ → static/build), with Node from the machine or from PyPI; the same
# npm then installs roslib for the rosbridge client test (tests/js, pinned by its lock file).
web_build
npm ci --prefix tests/js --no-audit --no-fund --loglevel=error >/dev/null

exec env TELEOP_VENV="$VENV" bash scripts/check "$@"
