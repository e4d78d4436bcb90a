"""A workspace far past the API's limits (a node filled it: 600 MiB on disk, ten files of 60 MiB
that deflate cannot shrink) is still the student's to download, and ``GET /api/workspace/archive``
on a live server sends it without holding it in memory: the server's peak resident memory (VmHWM)
rises by less than 100 MiB while it builds and sends the zip, and the zip it sent is whole (every
entry's size and checksum). The big files are stored as they are, a source file beside them is
deflated. Before, the zip was built in memory: a 960 MiB workspace took the server from 192 MiB
to 3 GiB."""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

import pytest
from support.app import App
from support.http import HTTP

pytestmark = pytest.mark.timing  # the server's peak memory, read across real seconds: run alone

COUNT = 10
FILE_MIB = 60
MAX_RISE_MIB = 100
MIB = 1024 * 1024
NODE = "import rclpy\n\n\ndef main():\n    rclpy.init()\n" * 20


def peak_kib(pid: int) -> int:
    """The process's peak resident memory (VmHWM), in KiB."""
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1])
    raise AssertionError(f"no VmHWM for process {pid}")


def block() -> bytes:
    """1 MiB of random bytes: repeated, still nothing deflate can shrink (its window is 32 KiB)."""
    return os.urandom(MIB)


def test_large_archive_is_sent_whole_from_disk_not_memory(tmp_path: Path) -> None:
    logs = tmp_path / "workspace" / "logs"
    logs.mkdir(parents=True)
    (tmp_path / "workspace" / "node.py").write_text(NODE)
    data = block()
    for index in range(COUNT):
        with (logs / f"run{index}.log").open("wb") as out:
            for _ in range(FILE_MIB):
                out.write(data)
    app = App(tmp_path, "--launch", "rocket", "start_delay:=3600", "--no-foxglove", cwd=tmp_path)
    received = tmp_path / "received.zip"
    try:
        assert app.get("/api/workspace/files")["entries"]  # the route's code is loaded before the peak
        before = peak_kib(app.proc.pid)
        with HTTP.stream("GET", f"{app.url}/api/workspace/archive", timeout=120.0) as reply:
            assert reply.status_code == 200, reply.read()[:500]
            with received.open("wb") as out:
                for chunk in reply.iter_bytes():
                    out.write(chunk)
            assert int(reply.headers["content-length"]) == os.path.getsize(received)
        rise_mib = (peak_kib(app.proc.pid) - before) / 1024
    finally:
        app.stop()
    assert rise_mib < MAX_RISE_MIB, f"the server's peak memory rose by {rise_mib:.0f} MiB"
    with zipfile.ZipFile(received) as archive:
        infos = {i.filename: i for i in archive.infolist()}
        logs = [f"logs/run{i}.log" for i in range(COUNT)]
        assert sorted(infos) == sorted([*logs, "node.py"])
        assert all(infos[log].file_size == FILE_MIB * MIB for log in logs)
        assert all(infos[log].compress_type == zipfile.ZIP_STORED for log in logs)
        assert infos["node.py"].compress_type == zipfile.ZIP_DEFLATED
        assert archive.read("node.py").decode() == NODE
        assert archive.testzip() is None  # every entry reads back to bytes of its checksum
