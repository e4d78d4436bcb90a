"""A world's progress handed from one place to the next (server/world/checkpoints/handover.py) and the class
server's copies of the progress its world workers keep in folders of their own
(server/classroom/progress_copies.py), against a worker directory that answers as a worker's
route does: the copy is asked for what changed only, written whole, handed to a worker that keeps
its own folder and never to one that shares the class server's."""

from __future__ import annotations

import asyncio
import base64
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from server.classroom.errors import WorkerFailedError
from server.classroom.progress_copies import PROGRESS_PATH, ProgressCopies
from server.classroom.workers import WorkerRef
from server.classroom.world import World
from server.world.checkpoints.catalog import load
from server.world.checkpoints.handover import from_wire, tag, to_wire
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.saved import SavedProgressError, Snapshot
from server.world.checkpoints.store import ProgressStore

from .test_api import tiny_png

CHECKPOINTS = load()


def progress_with_everything() -> Progress:
    progress = Progress(CHECKPOINTS)
    progress.met("fly_to_point", {"rate_hz": 1.0, "track": [[0.0, 0.0, 0.0], [5.0, 5.0, 10.0]]})
    progress.answer("q1", "four nodes")
    progress.capture("fly_to_point", tiny_png())
    return progress


@pytest.fixture
def store(tmp_path: Path) -> Iterator[ProgressStore]:
    made = ProgressStore.in_state_dir(tmp_path / "class")
    yield made
    made.close()


def test_handover_round_trip_keeps_records_answers_and_captures() -> None:
    progress = progress_with_everything()
    back = from_wire(to_wire(Snapshot.of(progress)), CHECKPOINTS)
    assert back.records == progress.records
    assert back.answers["q1"] == progress.answers["q1"]
    assert back.captures == {"fly_to_point": tiny_png()}


def test_a_tag_changes_with_each_change_and_differs_between_two_progresses() -> None:
    one, other = Progress(CHECKPOINTS), Progress(CHECKPOINTS)
    before = tag(one)
    assert tag(other) != before  # same version, another world's state
    one.answer("q1", "x")
    assert tag(one) != before


@pytest.mark.parametrize(
    ("body", "named"),
    [
        ([], "not a handed-over progress"),
        ({"progress": {"format": 99}}, "format"),
        ({"progress": None}, "not a handed-over progress"),
        ({"progress": {}, "captures": []}, "'captures' is not an object"),
        ({"progress": "x"}, "not a handed-over progress"),
    ],
)
def test_handover_refuses_what_is_not_progress(body: Any, named: str) -> None:
    with pytest.raises(SavedProgressError, match=named):
        from_wire(body, CHECKPOINTS)


def test_handover_refuses_a_capture_that_is_no_png_or_of_no_checkpoint() -> None:
    good = to_wire(Snapshot.of(progress_with_everything()))
    for captures, named in (
        ({"fly_to_point": base64.b64encode(b"GIF89a").decode()}, "not a PNG"),
        ({"fly_to_point": "&&&"}, "not base64"),
        ({"no_such_checkpoint": good["captures"]["fly_to_point"]}, "no checkpoint of this lab"),
    ):
        with pytest.raises(SavedProgressError, match=named):
            from_wire({**good, "captures": captures}, CHECKPOINTS)


def test_store_put_writes_a_copy_whole_and_snapshot_reads_it_back(store: ProgressStore) -> None:
    assert store.snapshot("ada", CHECKPOINTS) is None  # no copy yet
    first = progress_with_everything()
    store.put("ada", Snapshot.of(first))
    read = store.snapshot("ada", CHECKPOINTS)
    assert read is not None and read.records == first.records and read.captures == first.captures
    # A newer copy without the capture replaces the old one whole: no stale picture stays.
    second = Progress(CHECKPOINTS)
    second.answer("q1", "five nodes")
    store.put("ada", Snapshot.of(second))
    read = store.snapshot("ada", CHECKPOINTS)
    assert read is not None and read.captures == {} and read.records == {}
    assert read.answers["q1"].text == "five nodes"
    assert not list(store.world_folder("ada").glob("*.png"))


def test_store_put_stops_an_older_progress_of_the_world_saving(store: ProgressStore) -> None:
    old = store.open("ada", CHECKPOINTS)
    store.put("ada", Snapshot.of(progress_with_everything()))
    old.answer("q1", "an older state's answer")  # it would overwrite the copy if it still saved
    assert store.flush()
    read = store.snapshot("ada", CHECKPOINTS)
    assert read is not None and read.answers["q1"].text == "four nodes"


class Workers:
    """A worker directory whose one worker answers the progress route from ``hosted``."""

    def __init__(self, hosted: dict[str, Progress]) -> None:
        self.hosted = hosted
        self.asked: list[dict[str, str]] = []
        self.down = False

    async def checked(
        self, ref: WorkerRef, method: str, path: str, *, world: str | None = None, body: Any = None
    ) -> Any:
        assert (method, path) == ("POST", PROGRESS_PATH)
        if self.down:
            raise WorkerFailedError(f"world worker {ref.id!r} did not answer")
        self.asked.append(dict(body["known"]))
        return {
            "worlds": {
                name: {"tag": tag(p), "progress": to_wire(Snapshot.of(p))}
                for name, p in self.hosted.items()
                if body["known"].get(name) != tag(p)
            }
        }


def ref(mark: str | None) -> WorkerRef:
    return WorkerRef("wa", "http://127.0.0.1:1", 1, 4, "token", progress_mark=mark)


def test_copies_ask_for_what_changed_write_it_and_hand_it_over(store: ProgressStore) -> None:
    copies = ProgressCopies(store, CHECKPOINTS)
    copies.leave_mark()
    own_folder = ref("another-folders-mark")
    ada = Progress(CHECKPOINTS)
    ada.answer("q1", "first answer")
    workers = Workers({"ada": ada})
    worlds = {"ada": World("ada", "Ada", "t1", None, None, worker=own_folder)}  # type: ignore[arg-type]

    asyncio.run(copies.refresh(workers, worlds, [own_folder]))  # type: ignore[arg-type]
    asyncio.run(copies.refresh(workers, worlds, [own_folder]))  # type: ignore[arg-type]
    assert workers.asked == [{}, {"ada": tag(ada)}]  # the second round names the copy it has
    copy = store.snapshot("ada", CHECKPOINTS)
    assert copy is not None and copy.answers["q1"].text == "first answer"

    ada.answer("q1", "second answer")
    workers.down = True  # a round the worker misses changes nothing here
    asyncio.run(copies.refresh(workers, worlds, [own_folder]))  # type: ignore[arg-type]
    workers.down = False
    asyncio.run(copies.refresh(workers, worlds, [own_folder]))  # type: ignore[arg-type]
    handed = asyncio.run(copies.handover(ref("a-third-folders-mark"), "ada"))
    assert handed is not None
    assert from_wire(handed, CHECKPOINTS).answers["q1"].text == "second answer"


def test_copies_leave_alone_a_worker_that_shares_the_folder(store: ProgressStore) -> None:
    copies = ProgressCopies(store, CHECKPOINTS)
    copies.leave_mark()
    sharing = ref(copies.mark)
    ada = Progress(CHECKPOINTS)
    ada.answer("q1", "kept in the shared folder by the worker")
    workers = Workers({"ada": ada})
    worlds = {"ada": World("ada", "Ada", "t1", None, None, worker=sharing)}  # type: ignore[arg-type]
    asyncio.run(copies.refresh(workers, worlds, [sharing]))  # type: ignore[arg-type]
    assert workers.asked == [] and store.snapshot("ada", CHECKPOINTS) is None
    store.put("ada", Snapshot.of(ada))
    assert asyncio.run(copies.handover(sharing, "ada")) is None  # it reads the folder itself
    assert asyncio.run(copies.handover(ref("its-own-mark"), "ada")) is not None
