"""The suite's schedule: the files it starts first are files of the suite, and they do start first."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from support.schedule import (
    BROWSER_FOLDER,
    LONGEST_FILES,
    TIMING_MARK,
    browser_tests_astray,
    timing_tests_unfound,
)

REPO = Path(__file__).resolve().parents[1]


def test_every_file_the_schedule_starts_first_is_one_of_the_suites() -> None:
    missing = [path for path in LONGEST_FILES if not (REPO / path).is_file()]
    assert missing == [], f"LONGEST_FILES names files that are gone: {missing}"
    assert len(set(LONGEST_FILES)) == len(LONGEST_FILES)


def test_collection_puts_the_longest_files_first_in_their_order() -> None:
    """pytest --co over three files named out of order: the listed ones first, by the list."""
    first, second = LONGEST_FILES[0], LONGEST_FILES[1]
    other = "tests/test_settings.py"
    assert other not in LONGEST_FILES
    listed = subprocess.run(
        [sys.executable, "-m", "pytest", "--co", "-q", "-p", "no:cacheprovider", other, second, first],
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    ).stdout.splitlines()
    files = [line.split("::", 1)[0] for line in listed if "::" in line]
    order = list(dict.fromkeys(files))
    assert order == [first, second, other], order


class FakeItem(pytest.Item):
    """Just a node id and its markers, as the schedule reads a collected test."""

    def runtest(self) -> None:  # pragma: no cover - never run
        raise AssertionError("a schedule's stand-in is not a test")


def fake_item(session: pytest.Session, nodeid: str, *markers: str, path: Path | None = None) -> FakeItem:
    item = FakeItem.from_parent(
        session, name=nodeid, nodeid=nodeid, path=path or REPO / nodeid.split("::")[0]
    )
    for marker in markers:
        item.add_marker(marker)
    return item


def test_a_browser_test_outside_the_browser_folder_is_named_and_one_inside_is_not(
    request: pytest.FixtureRequest,
) -> None:
    session = request.session
    inside = fake_item(session, f"{BROWSER_FOLDER}test_page_browser.py::test_a", "browser")
    outside = fake_item(session, "tests/api/test_topics.py::test_b", "browser")
    plain = fake_item(session, "tests/api/test_topics.py::test_c")
    assert browser_tests_astray([inside, outside, plain]) == [outside.nodeid]
    assert browser_tests_astray([inside, plain]) == []


def test_a_timing_test_whose_file_does_not_say_its_mark_is_named(
    request: pytest.FixtureRequest, tmp_path: Path
) -> None:
    """The gate's timing part collects the files that hold TIMING_MARK; a test marked another way
    (by a hook, say) would run in no part, and the collection refuses it."""
    said = tmp_path / "test_said.py"
    said.write_text(f"pytestmark = pytest.{TIMING_MARK}\n")
    unsaid = tmp_path / "test_unsaid.py"
    unsaid.write_text("pytestmark = TIMED\n")
    session = request.session
    items = [
        fake_item(session, "test_said.py::test_a", "timing", path=said),
        fake_item(session, "test_unsaid.py::test_b", "timing", path=unsaid),
        fake_item(session, "test_unsaid.py::test_c", path=unsaid),
    ]
    assert timing_tests_unfound(items) == ["test_unsaid.py::test_b"]
    assert timing_tests_unfound(items[:1] + items[2:]) == []
