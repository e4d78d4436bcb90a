"""A world's progress on disk (server/world/checkpoints/store.py): written by the store's thread, read back
whole, limited on the way in as on the way out; a bad file is logged and read as no progress."""

from __future__ import annotations

import json
import logging
from collections.abc import Iterator
from pathlib import Path

import pytest

from server.world.checkpoints.catalog import load
from server.world.checkpoints.progress import MAX_ANSWER_BYTES, MAX_CAPTURE_BYTES, PNG_MAGIC
from server.world.checkpoints.store import PROGRESS_FILE, ProgressStore

from .test_api import tiny_png

CHECKPOINTS = load()


@pytest.fixture
def store(tmp_path: Path) -> Iterator[ProgressStore]:
    made = ProgressStore.in_state_dir(tmp_path)
    yield made
    made.close()


def saved(store: ProgressStore, world: str) -> dict[str, object]:
    assert store.flush(), "the writer did not catch up"
    body: dict[str, object] = json.loads((store.world_folder(world) / PROGRESS_FILE).read_bytes())
    return body


def test_store_met_answered_captured_is_read_back_whole_after_a_new_store(tmp_path: Path) -> None:
    first = ProgressStore.in_state_dir(tmp_path)
    progress = first.open("ada", CHECKPOINTS)
    assert not progress.records and not progress.captures  # nothing saved yet: empty
    progress.met("fly_to_point", {"rate_hz": 1.0, "track": [[0.0, 0.0, 0.0], [5.0, 5.0, 10.0]]})
    progress.met("fly_to_point", {"rate_hz": 1.1, "track": []})  # the newest evidence wins, counted
    progress.answer("q1", "four nodes")
    png = tiny_png()
    progress.capture("fly_to_point", png)
    first.close()  # writes what waits

    second = ProgressStore.in_state_dir(tmp_path)
    again = second.open("ada", CHECKPOINTS)
    record = again.records["fly_to_point"]
    assert record.evidence == {"rate_hz": 1.1, "track": []} and record.times == 2
    assert record.done_at_s == progress.records["fly_to_point"].done_at_s
    assert again.answers["q1"].text == "four nodes"
    assert again.answers["q1"].saved_at_s == progress.answers["q1"].saved_at_s
    assert again.captures == {"fly_to_point": png}
    assert again.version > 0  # a page that asks ?since=0 hears of it
    other = second.open("bob", CHECKPOINTS)  # another world's files are its own
    assert not other.records and other.answers["q1"].text == ""
    second.close()


def test_store_a_file_that_is_not_progress_is_logged_set_aside_and_read_as_none(
    store: ProgressStore, caplog: pytest.LogCaptureFixture
) -> None:
    folder = store.world_folder("ada")
    folder.mkdir(parents=True)
    cases = [b"{not json", b'{"format": 99, "records": {}, "answers": {}}', b"[1, 2]", b'{"format": 1}']
    for junk in cases:
        (folder / PROGRESS_FILE).write_bytes(junk)
        with caplog.at_level(logging.WARNING, logger="checkpoints"):
            progress = store.open("ada", CHECKPOINTS)
        assert not progress.records and all(a.text == "" for a in progress.answers.values())
        assert str(folder / PROGRESS_FILE) in caplog.text, junk
        assert (folder / f"{PROGRESS_FILE}.corrupt").read_bytes() == junk
        caplog.clear()
    # The world goes on: its next change is saved as a good file again.
    progress.answer("final", "one command")
    assert saved(store, "ada")["answers"] == {
        "final": {"text": "one command", "saved_at_s": pytest.approx(progress.answers["final"].saved_at_s)}
    }


def test_store_takes_only_what_the_lab_declares_within_its_limits(store: ProgressStore) -> None:
    folder = store.world_folder("ada")
    folder.mkdir(parents=True)
    good = {"done_at_s": 1_700_000_000.0, "times": 1, "evidence": {"rate_hz": 1.0}}
    body = {
        "format": 1,
        "records": {
            "fly_to_point": good,
            "no_such_checkpoint": good,
            "keyboard_abort": {**good, "times": 0},
            "launch_and_keys": {**good, "done_at_s": "yesterday"},
        },
        "answers": {
            "q1": {"text": "fine", "saved_at_s": 1.0},
            "q2": {"text": "x" * (MAX_ANSWER_BYTES + 1), "saved_at_s": 1.0},
            "nope": {"text": "an unknown question", "saved_at_s": 1.0},
        },
    }
    (folder / PROGRESS_FILE).write_text(json.dumps(body))
    (folder / "keyboard_abort.png").write_bytes(b"GIF89a not a png")
    (folder / "launch_and_keys.png").write_bytes(PNG_MAGIC + b"\0" * MAX_CAPTURE_BYTES)
    (folder / "fly_to_point.png").write_bytes(tiny_png())
    progress = store.open("ada", CHECKPOINTS)
    assert list(progress.records) == ["fly_to_point"]
    assert progress.answers["q1"].text == "fine" and progress.answers["q2"].text == ""
    assert "nope" not in progress.answers
    assert list(progress.captures) == ["fly_to_point"]


def test_store_remove_deletes_the_worlds_files_and_its_progress_saves_nothing_more(
    store: ProgressStore,
) -> None:
    ada, bob = store.open("ada", CHECKPOINTS), store.open("bob", CHECKPOINTS)
    ada.answer("q1", "a")
    bob.answer("q1", "b")
    assert saved(store, "ada") and saved(store, "bob")
    assert store.remove("ada") is True
    assert not store.world_folder("ada").exists()
    ada.answer("q2", "after removal")  # a request that raced the removal
    bob.answer("q2", "still saved")  # the marker: the writer ran after it
    assert saved(store, "bob")["answers"]["q2"]["text"] == "still saved"  # type: ignore[index]
    assert not store.world_folder("ada").exists()
    assert store.remove("ada") is False  # nothing left to remove


@pytest.mark.parametrize("name", ["../ada", "ada/../../x", "", ".", "..", "a" * 65, "-x", "/etc"])
def test_store_refuses_a_world_name_that_is_not_one_plain_name(store: ProgressStore, name: str) -> None:
    with pytest.raises(ValueError, match="not a world's name"):
        store.world_folder(name)
    with pytest.raises(ValueError):
        store.remove(name)
    assert store.world_folder("ada_lovelace") == store.folder / "ada_lovelace"  # a plain one is fine


def test_store_evidence_that_is_not_json_fails_that_write_only_and_is_logged(
    store: ProgressStore, caplog: pytest.LogCaptureFixture
) -> None:
    ada, bob = store.open("ada", CHECKPOINTS), store.open("bob", CHECKPOINTS)
    with caplog.at_level(logging.ERROR, logger="checkpoints"):
        ada.met("fly_to_point", {"not_json": object()})
        assert store.flush()
    assert "progress of world ada not saved" in caplog.text
    bob.answer("q1", "the writer goes on")  # the marker: written by the same thread, after it
    assert saved(store, "bob")["answers"]["q1"]["text"] == "the writer goes on"  # type: ignore[index]
    assert not (store.world_folder("ada") / PROGRESS_FILE).exists()


def test_a_class_folder_is_read_bounded_with_owners_names_and_nothing_moved(tmp_path: Path) -> None:
    """saved_worlds.py: the class worlds with a progress file, by name, at most ``limit`` folders;
    a spoilt file is left where it is (the world's own start sets it aside), the lab's own is not
    a class world's, and a released owner record is kept beside under a name of its own."""
    from server.world.checkpoints.owner import OWNER_FILE, Owner
    from server.world.checkpoints.saved_worlds import read_saved

    store = ProgressStore.in_state_dir(tmp_path)
    try:
        for world in ("ada", "bob", "cy", "_lab"):
            store.open(world, CHECKPOINTS).answer("q1", f"{world}'s answer")
        store.claim("ada", Owner.of("Ada L.", "token-of-ada"))
        store.claim("dee", Owner.of("Dee", "token-of-dee"))  # an owner, no progress: not listed
        assert store.flush()
    finally:
        store.close()
    spoilt = store.world_folder("cy") / PROGRESS_FILE
    spoilt.write_text("{")
    found = read_saved(store.folder, CHECKPOINTS)
    assert [(s.world, s.progress.student) for s in found] == [("ada", "Ada L."), ("bob", "bob")]
    assert found[0].progress.answers["q1"].text == "ada's answer" and not found[0].progress.captures
    assert spoilt.read_text() == "{"  # left as it is
    assert len(read_saved(store.folder, CHECKPOINTS, limit=1)) <= 1
    assert store.owner("ada") == Owner.of("Ada L.", "token-of-ada")
    aside = [store.release("ada", "20240101T000000Z"), store.release("dee", "20240101T000000Z")]
    store.claim("ada", Owner.of("Ada L.", "again"))
    again = store.release("ada", "20240101T000000Z")  # the same second: both kept
    assert aside[0] is not None and again is not None and aside[0] != again and aside[0].exists()
    assert store.owner("ada") is None and store.release("bob", "x") is None
    assert sorted(p.name for p in store.world_folder("ada").glob(f"{OWNER_FILE}*")) == [
        f"{OWNER_FILE}.released-20240101T000000Z",
        f"{OWNER_FILE}.released-20240101T000000Z-2",
    ]


def test_a_join_writes_its_owner_at_once_and_progress_keeps_it(tmp_path: Path) -> None:
    """Code a student writes before any progress is theirs too: the owner is on disk from the join."""
    from server.world.checkpoints.owner import OWNER_FILE, Owner

    store = ProgressStore.in_state_dir(tmp_path)
    try:
        store.claim("eve", Owner.of("Eve", "token-of-eve"))
        assert (store.world_folder("eve") / OWNER_FILE).is_file() and not store.has_progress("eve")
        assert store.owner("eve") == Owner.of("Eve", "token-of-eve")
        store.open("eve", CHECKPOINTS).answer("q1", "Eve's answer")
        assert store.flush()
    finally:
        store.close()
    assert store.has_progress("eve")
    assert store.owner("eve") == Owner.of("Eve", "token-of-eve")
