"""Fixtures shared by the unit tests: a bus on a manual clock, and its executor; and a working
folder of each test's own.

Time moves only when a test moves it (``executor.spin_until`` / ``spin_for``).
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from support.ctrl_c import pytest_configure as pytest_configure  # Ctrl-C back for what the tests start
from support.schedule import (
    BROWSER_FOLDER,
    TIMING_MARK,
    browser_tests_astray,
    longest_files_first,
    timing_tests_unfound,
)

from node_runtime.bus import Bus, Executor, ManualClock


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The longest files first (support.schedule); a browser test outside tests/browser/ is an
    error, as the check gate's browser part collects only there, and so is a timing test whose file
    does not say ``pytest.mark.timing``, as its timing part collects only the files that do."""
    astray = browser_tests_astray(items)
    if astray:
        raise pytest.UsageError(f"browser tests belong in {BROWSER_FOLDER}: {astray}")
    unfound = timing_tests_unfound(items)
    if unfound:
        raise pytest.UsageError(f"mark timing tests with pytest.{TIMING_MARK} in their own file: {unfound}")
    items[:] = longest_files_first(items)


@pytest.fixture(scope="session", autouse=True)
def session_folder(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """The working folder of the fixtures that outlive one test (a module's app, a session's):
    one per pytest process, never the repository's."""
    with pytest.MonkeyPatch.context() as patch:
        folder = tmp_path_factory.mktemp("cwd")
        patch.chdir(folder)
        yield folder


@pytest.fixture(autouse=True)
def own_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """Each test runs in a folder of its own: what an app made in the test keeps in its working
    folder by default (``state/``, ``workspaces/``, ``bags/``) is never another test's."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock()


@pytest.fixture
def bus(clock: ManualClock) -> Bus:
    return Bus(clock)


@pytest.fixture
def executor(bus: Bus) -> Executor:
    return Executor(bus)
