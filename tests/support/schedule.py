"""The order in which the check gate's workers take the test files."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TypeVar

import pytest

# The browser tests' folder: the check gate's browser part collects only this one, and its
# parallel part all but this one.
BROWSER_FOLDER = "tests/browser/"
# What the file of every timing test holds (as ``pytest.mark.timing``): the check gate's timing part
# collects only the files that hold it (scripts/check greps for it), not the whole suite.
TIMING_MARK = "mark.timing"

# The test files that take longest in their part of the suite (pytest --durations on this 2-core
# machine), in that order. The check gate hands out whole files to its workers in collection order
# (--no-loadscope-reorder), so these go first: started last, one of them would keep its worker
# busy after the others finished.
# Only the schedule depends on this list; tests/test_schedule.py checks that each file exists.
LONGEST_FILES = (
    # The browser part's, every file (it has 12 for its workers; one of the longer ones, left off
    # this list, started last and kept a worker busy 20 s after the other finished)
    "tests/browser/test_page_browser.py",
    "tests/browser/test_teleop_browser.py",
    "tests/browser/test_editor_browser.py",
    "tests/browser/test_workbench_browser.py",
    "tests/browser/test_classroom_browser.py",
    "tests/browser/test_guide_browser.py",
    "tests/browser/test_class_code_browser.py",
    "tests/browser/test_rocket_browser.py",
    "tests/browser/test_instructor_checkpoints_browser.py",
    "tests/browser/test_graph_browser.py",
    "tests/browser/test_world_worker_browser.py",
    "tests/browser/test_record_browser.py",
    # The parallel part's
    "tests/contract/test_class_schemathesis.py",
    "tests/contract/test_openapi_schemathesis.py",
    "tests/classroom/test_worker_failover.py",
    "tests/checkpoints/test_live.py",
    "tests/processes/test_handout_nodes.py",
    "tests/classroom/test_worker_workspaces.py",
    "tests/listeners/test_every_port.py",
    "tests/interop/test_zenoh_ros2_sdk.py",
    "tests/classroom/test_local_workers.py",
    "tests/processes/test_faults.py",
    "tests/checkpoints/test_worker_rows.py",
    "tests/sandbox/test_sandbox.py",
    "tests/checkpoints/test_restart.py",
    "tests/workspace/test_action_tutorial.py",
    "tests/workspace/test_launch_tutorials.py",
    "tests/workspace/test_tf2_tutorials.py",
    "tests/checkpoints/test_class_restart.py",
    "tests/checkpoints/test_api.py",
    "tests/differential/test_programs.py",
)

Test = TypeVar("Test", bound=pytest.Item)


def longest_files_first(items: Sequence[Test]) -> list[Test]:
    """The tests of LONGEST_FILES first, in its order; the rest after them as collected."""
    rank = {path: index for index, path in enumerate(LONGEST_FILES)}
    return sorted(items, key=lambda item: rank.get(item.nodeid.split("::", 1)[0], len(rank)))


def browser_tests_astray(items: Sequence[pytest.Item]) -> list[str]:
    """The browser tests that are not in BROWSER_FOLDER."""
    return [
        item.nodeid
        for item in items
        if item.get_closest_marker("browser") is not None and not item.nodeid.startswith(BROWSER_FOLDER)
    ]


def timing_tests_unfound(items: Sequence[pytest.Item]) -> list[str]:
    """The timing tests whose file does not hold TIMING_MARK (a mark given some other way): the
    check gate's timing part would not collect them, and the other parts leave them out."""
    holds: dict[Path, bool] = {}
    unfound = []
    for item in items:
        if item.get_closest_marker("timing") is None:
            continue
        if item.path not in holds:
            holds[item.path] = TIMING_MARK in item.path.read_text(encoding="utf-8")
        if not holds[item.path]:
            unfound.append(item.nodeid)
    return unfound
