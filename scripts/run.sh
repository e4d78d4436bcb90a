#!/usr/bin/env bash
# Set up (a virtual environment in .venv, the app and its pinned dependencies, the page's scripts
# built from web/) and run the lab on http://127.0.0.1:8000/ . Extra arguments go to `python -m server` (e.g. --launch rocket).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/_venv.sh
source scripts/_web.sh
install_once .
web_build
exec "$VENV/bin/python" -m server "$@"
