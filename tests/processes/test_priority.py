"""A node process lowered below the sims' loop (node_runtime/process/priority.py): its niceness, and its
session's scheduling group only when it leads that session, so a node started in a terminal's
session never lowers the terminal's other processes. Each case runs in a child process of its own."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from support.app import REPO

from node_runtime.process.priority import group_nice, session_group_nice

GROUP = Path("/proc/self/autogroup")
PROBE = (
    "import os\n"
    "from node_runtime.process.priority import run_below_sims, session_group_nice\n"
    "run_below_sims(5)\n"
    "print(os.getpriority(os.PRIO_PROCESS, 0), session_group_nice(os.getpid()))\n"
)


def lowered(*, own_session: bool) -> tuple[int, str]:
    out = subprocess.run(
        [sys.executable, "-c", PROBE],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=60,
        start_new_session=own_session,
        check=True,
    ).stdout.split()
    return int(out[0]), out[1]


def own_group() -> str:
    return str(session_group_nice(os.getpid()))  # "None" in the root group, whose line is empty


def test_a_group_line_gives_its_niceness_and_the_root_groups_empty_line_none() -> None:
    assert group_nice("/autogroup-42 nice 10\n") == 10
    assert group_nice("/autogroup-7 nice -3\n") == -3
    assert group_nice("") is None


@pytest.mark.parametrize("own_session", [True, False], ids=["leads its session", "in ours"])
def test_a_node_is_lowered_and_its_sessions_group_only_if_it_leads_it(own_session: bool) -> None:
    nice, group = lowered(own_session=own_session)
    assert nice == os.getpriority(os.PRIO_PROCESS, 0) + 5
    if not GROUP.exists():  # a kernel without autogroups: the niceness counts against everyone
        assert group == "None"
    elif own_session:
        assert group == "5"  # a new session's group starts at 0
    else:
        assert group == own_group()  # ours, as it was
