"""Ctrl-C for the processes the suite starts, whatever shell started the suite.

A shell without job control (a script's ``cmd &``, ``nohup cmd &``) starts its background jobs
with SIGINT ignored, and an ignored signal stays ignored in every process started from there on:
the node processes the tests stop with Ctrl-C, as ROS 2's tools stop them, would never see it, and
a Python started so does not install its Ctrl-C handler (13 tests failed so in one such run). The
suite gives SIGINT Python's own handler back; a process it starts then begins with SIGINT at its
default, as from a terminal. tests/conftest.py takes its hook; ``-p support.ctrl_c`` loads it alone.
"""

from __future__ import annotations

import signal

import pytest


def restore_ctrl_c() -> None:
    """Python's Ctrl-C handler where SIGINT was ignored; anything else is left as it is."""
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


def pytest_configure(config: pytest.Config) -> None:
    restore_ctrl_c()
