# Sourced by run.sh and test.sh: make .venv with a Python 3.11 or newer if it is not there, and
# install_once SPEC: take ROS 2's interface definitions from PyPI's wheels if they are not current
# (node_runtime/ros_wheels.py; quick once its cache holds them), then pip-install the project (SPEC: "."
# or ".[test]") only when pyproject.toml or the checkout's place changed since the last install of
# that SPEC (the install is editable, so code changes need none). TELEOP_REINSTALL=1 forces it.
# It compiles the lab's code every time (compile_lab).
VENV="${TELEOP_VENV:-.venv}"
if [ ! -x "$VENV/bin/python" ]; then
  PY=""
  for candidate in python3.13 python3.12 python3.11 python3; do
    if command -v "$candidate" >/dev/null 2>&1 &&
       "$candidate" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else 1)' 2>/dev/null; then
      PY="$candidate"; break
    fi
  done
  if [ -z "$PY" ]; then
    echo "Python 3.11 or newer is needed (python3 --version says: $(python3 --version 2>&1))." >&2
    exit 1
  fi
  "$PY" -m venv "$VENV"
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check --upgrade pip
fi

ros_interfaces() {  # ROS 2's definitions (std_msgs ...) from PyPI's wheels: node_runtime/ros_wheels.py
  "$VENV/bin/python" -m node_runtime.ros_wheels || {
    echo "The lab's messages need ROS 2's interface definitions from PyPI: see the error above." >&2
    exit 1
  }
}

# The lab's own code compiled to bytecode beside it (__pycache__, as Python keeps it): a node
# process runs with PYTHONDONTWRITEBYTECODE (a student's folder gets no __pycache__ in the page's
# tree), so it never wrote the lab's bytecode, and every node start compiled each lab module it
# imports again: a node's imports took 0.22 CPU-s so, 0.14 to 0.18 from bytecode (bench/start_cpu.py).
# Quick when nothing changed.
compile_lab() {
  env -u PYTHONPYCACHEPREFIX "$VENV/bin/python" -m compileall -q -j0 node_runtime server sim api client \
    >/dev/null 2>&1 ||
    echo "The lab's code could not be compiled beside it (python -m compileall): its node processes will compile it as they start." >&2
}

install_once() {
  local spec="$1"
  ros_interfaces
  compile_lab
  local stamp="$VENV/.installed-$(printf '%s' "$spec" | tr -c 'a-z' '_')"
  local want
  want="$(cksum < pyproject.toml) $(pwd)"
  if [ "${TELEOP_REINSTALL:-0}" != 1 ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    return 0
  fi
  echo "Installing the lab and its pinned dependencies ($spec) into $VENV ..."
  # setuptools reports "Editable installation" through the warnings module although it is only
  # information (its own InformationOnly class); every other warning still shows.
  PYTHONWARNINGS="ignore:Editable installation" \
    "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check -e "$spec"
  printf '%s\n' "$want" > "$stamp"
}
