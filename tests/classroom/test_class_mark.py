"""The mark that tells a world worker shares the class's workspaces folder: left once and kept,
read the same through any path to the folder, absent or not a mark elsewhere."""

from __future__ import annotations

from pathlib import Path

from server.services.workspace.class_mark import MARK_FILE, leave_mark, read_mark


def test_a_mark_is_left_once_and_read_through_any_path_to_the_folder(tmp_path: Path) -> None:
    folder = tmp_path / "class" / "workspaces"
    mark = leave_mark(folder)  # the folder is made
    assert read_mark(folder) == mark and leave_mark(folder) == mark  # kept across restarts
    (tmp_path / "mount").symlink_to(folder)  # the same folder by another path (a mount)
    assert read_mark(tmp_path / "mount") == mark
    assert [p.name for p in folder.iterdir()] == [MARK_FILE]  # nothing else left behind


def test_another_folder_or_a_file_that_is_no_mark_reads_as_none(tmp_path: Path) -> None:
    leave_mark(tmp_path / "class")
    assert read_mark(tmp_path / "elsewhere") is None
    odd = tmp_path / "odd"
    odd.mkdir()
    for text in ("", "not a mark!", "x" * 65):
        (odd / MARK_FILE).write_text(text)
        assert read_mark(odd) is None
    (odd / MARK_FILE).write_text("0123abcd\n")
    assert read_mark(odd) == "0123abcd"
