"""What the API writes is readable by all, whatever the server's umask: a sandboxed node runs as
its world's uid and reads its workspace bound read-only (docs/sandbox.md). A save, a new folder
on its way and an upload, through the real app under a umask that would keep them the server's
alone."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest

from .helpers import FILES, lab_client, lab_settings, save, zip_of


@pytest.fixture
def strict_umask() -> Iterator[None]:
    before = os.umask(0o077)
    try:
        yield
    finally:
        os.umask(before)


def mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


def test_file_modes_saves_folders_and_uploads_are_readable_by_all(tmp_path: Path, strict_umask: None) -> None:
    workspace = tmp_path / "ws"
    workspace.mkdir()
    (workspace / "plain.txt").write_text("made under the strict umask\n")
    assert mode(workspace / "plain.txt") == 0o600  # the umask holds for what the API does not write
    with lab_client(lab_settings(workspace)) as client:
        assert save(client, "src/pkg/node.py", "print('hi')\n").status_code == 201
        uploaded = client.post(
            f"{FILES[: -len('/files')]}/archive",
            content=zip_of({"src/other/a.py": "x = 1\n"}),
            headers={"content-type": "application/zip"},
        )
        assert uploaded.status_code in (200, 201), uploaded.text
    assert mode(workspace / "src" / "pkg" / "node.py") == 0o644
    assert mode(workspace / "src" / "other" / "a.py") == 0o644
    assert (
        mode(workspace / "src")
        == mode(workspace / "src" / "pkg")
        == mode(workspace / "src" / "other")
        == 0o755
    )
