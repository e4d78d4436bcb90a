"""The suite gives Ctrl-C back to the processes it starts when it was itself started with SIGINT
ignored, as a script's background job is (support/ctrl_c.py): a pytest started so, on a test whose
child process must begin with SIGINT at its default, fails without the plugin and passes with it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).resolve().parent
CHILD_TEST = """
import signal
import subprocess
import sys

HANDLER = "import signal, sys; sys.exit(0 if signal.getsignal(signal.SIGINT) is signal.default_int_handler else 3)"


def test_a_child_process_begins_with_ctrl_c():
    assert subprocess.run([sys.executable, "-c", HANDLER], check=False).returncode == 0
"""


def pytest_ignoring_ctrl_c(folder: Path, *args: str) -> subprocess.CompletedProcess[str]:
    """pytest on CHILD_TEST alone (its own empty config), started with SIGINT ignored."""
    (folder / "test_child.py").write_text(CHILD_TEST)
    (folder / "pytest.ini").write_text("[pytest]\n")
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-c", str(folder / "pytest.ini"),
         "--rootdir", str(folder), *args, str(folder / "test_child.py")],
        cwd=folder,
        env={**os.environ, "PYTHONPATH": str(TESTS), "PYTEST_DISABLE_PLUGIN_AUTOLOAD": "1"},
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN),
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )  # fmt: skip


def test_a_suite_started_with_ctrl_c_ignored_gives_it_back_to_what_it_starts(tmp_path: Path) -> None:
    ignored = pytest_ignoring_ctrl_c(tmp_path)
    assert ignored.returncode == 1 and "1 failed" in ignored.stdout, ignored.stdout + ignored.stderr
    restored = pytest_ignoring_ctrl_c(tmp_path, "-p", "support.ctrl_c")
    assert restored.returncode == 0 and "1 passed" in restored.stdout, restored.stdout + restored.stderr
