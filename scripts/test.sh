#!/usr/bin/env bash
# Set up what the tests need (the app, pytest, Playwright, Debian's Chromium) and run the whole
# suite. Extra arguments go to pytest. CI runs exactly this (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/_venv.sh
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

exec "$VENV/bin/python" -m pytest "$@"
