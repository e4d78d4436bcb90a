"""The workspace API against a process that writes in the same folder (a student's node): a link
left at a save's temporary name is not followed, a file swapped for a link to a secret and back
while it is read or zipped never gives the secret away, and folders nested past the depth limit
(1,100 of them, past Python's recursion limit) are listed, zipped, saved beside and removed.

Each attack has the ordinary thing beside it: the save still lands, the real text is still read,
the deep workspace's own files still list and zip."""

from __future__ import annotations

import io
import os
import shutil
import subprocess
import sys
import zipfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from classroom.test_classroom_api import auth, class_settings, join
from fastapi.testclient import TestClient

from node_runtime.bus import ManualClock
from server.app import create_app

from .helpers import FILES, lab_client, lab_settings, names_in, save, tree, upload, zip_of

SECRET = "another student's code: TOPSECRET\n"
REAL = "real = 1\n"
NESTED = 1_100  # past Python's recursion limit of 1,000
DEPTH = 16  # WorkspaceLimits.max_depth's default
# Names a save or an upload might stage its new file under, beside the file (the old fixed one first).
STAGING = (".{name}.saving", ".{name}.tmp", "{name}.saving", ".{name}.new", ".{name}~", "{name}~")


@pytest.fixture
def places(tmp_path: Path) -> tuple[Path, Path]:
    """A workspace, and another student's file outside it that the server may write."""
    workspace, other = tmp_path / "workspace", tmp_path / "otherworld" / "src" / "pkg" / "node.py"
    (workspace / "src" / "pkg").mkdir(parents=True)
    other.parent.mkdir(parents=True)
    other.write_text(SECRET)
    return workspace, other


def plant_links(folder: Path, name: str, target: Path) -> list[Path]:
    links = [folder / pattern.format(name=name) for pattern in STAGING]
    for link in links:
        link.symlink_to(target)
    return links


def test_hostile_a_link_at_a_saves_temporary_name_is_not_followed(places: tuple[Path, Path]) -> None:
    workspace, other = places
    folder = workspace / "src" / "pkg"
    with lab_client(lab_settings(workspace)) as client:
        assert save(client, "src/pkg/victim.py", "old = 1\n").status_code == 201
        links = plant_links(folder, "victim.py", other) + plant_links(folder, "fresh.py", other)
        over = save(client, "src/pkg/victim.py", "new = 2\n")
        created = save(client, "src/pkg/fresh.py", "fresh = 3\n", **{"If-None-Match": "*"})
        assert over.status_code == 200 and created.status_code == 201, (over.text, created.text)
        assert other.read_text() == SECRET  # the link's target is untouched
        for path, text in (("victim.py", "new = 2\n"), ("fresh.py", "fresh = 3\n")):
            assert not (folder / path).is_symlink() and (folder / path).read_text() == text
            assert client.get(f"{FILES}/src/pkg/{path}").json()["text"] == text
        assert all(link.is_symlink() for link in links)  # left alone, and never listed
        assert [e["path"] for e in tree(client)["entries"] if e["kind"] == "file"] == [
            "src/pkg/fresh.py",
            "src/pkg/victim.py",
        ]


@pytest.mark.parametrize("replace", [False, True], ids=["add", "replace"])
def test_hostile_a_link_at_an_uploads_temporary_name_is_not_followed(
    places: tuple[Path, Path], replace: bool
) -> None:
    workspace, other = places
    folder = workspace / "src" / "pkg"
    with lab_client(lab_settings(workspace)) as client:
        assert save(client, "src/pkg/up.py", "old = 1\n").status_code == 201
        plant_links(folder, "up.py", other)
        plant_links(folder, "new.py", other)
        route = "/api/workspace/archive?replace=true" if replace else "/api/workspace/archive"
        data = zip_of({"src/pkg/up.py": "up = 2\n", "src/pkg/new.py": "new = 3\n"})
        reply = client.post(route, content=data, headers={"content-type": "application/zip"})
        assert reply.status_code == 200, reply.text
        assert reply.json() == {"written": ["src/pkg/new.py", "src/pkg/up.py"]}
        assert other.read_text() == SECRET
        assert (folder / "up.py").read_text() == "up = 2\n" and not (folder / "up.py").is_symlink()
        assert (folder / "new.py").read_text() == "new = 3\n" and not (folder / "new.py").is_symlink()


# A node's process: swaps the file for a link to the secret and back as fast as it can, the path
# always there (each step a rename) and as long a link as a file (one more call each), for at most
# MAX_SWAPS swaps or MAX_S seconds; says "swapping" as it starts.
SWAPPER = """
import os, sys, time
target, secret, max_swaps, max_s = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
link, real, back = (os.path.join(os.path.dirname(target), n) for n in (".swap_link", ".swap_real", ".swap_back"))
os.link(target, real)  # the real file under a second name, for good
deadline = time.monotonic() + max_s
print("swapping", flush=True)
for _ in range(max_swaps):
    if time.monotonic() > deadline:
        break
    os.symlink(secret, link)
    os.replace(link, target)  # now a link to the secret
    os.link(real, back)
    os.replace(back, target)  # the real file again
"""
MAX_SWAPS = 50_000_000
MAX_S = 60.0
# Reads of the swapped file: at least MIN_READS, and on until the link was met LINKS_SEEN times
# (one read in ten to a hundred met it on a loaded 2-core machine), at most MAX_READS.
MIN_READS, LINKS_SEEN, MAX_READS = 300, 5, 3000


@pytest.fixture
def swapping(places: tuple[Path, Path]) -> Iterator[TestClient]:
    """The lab, while a process swaps ``src/pkg/swap.py`` for a link to another student's file and
    back (``src/pkg/steady.py`` beside it stays)."""
    workspace, other = places
    target = workspace / "src" / "pkg" / "swap.py"
    target.write_text(REAL)
    (workspace / "src" / "pkg" / "steady.py").write_text("steady = 1\n")
    with lab_client(lab_settings(workspace)) as client:
        swapper = subprocess.Popen(
            [sys.executable, "-c", SWAPPER, str(target), str(other), str(MAX_SWAPS), str(MAX_S)],
            stdout=subprocess.PIPE,
            text=True,
        )
        assert swapper.stdout is not None
        try:
            assert swapper.stdout.readline() == "swapping\n"
            yield client
            assert swapper.poll() is None, "the swapping ended before the test did"
        finally:
            swapper.terminate()
            swapper.wait(timeout=30)
            swapper.stdout.close()


def test_hostile_a_file_swapped_for_a_link_is_never_read_through_it(swapping: TestClient) -> None:
    client = swapping
    statuses: dict[int, int] = {}
    for count in range(1, MAX_READS + 1):
        if count > MIN_READS and statuses.get(422, 0) >= LINKS_SEEN:
            break
        reply = client.get(f"{FILES}/src/pkg/swap.py")
        assert "TOPSECRET" not in reply.text, "the secret was read through the link"
        statuses[reply.status_code] = statuses.get(reply.status_code, 0) + 1
        if reply.status_code == 200:
            assert reply.json()["text"] == REAL
        else:
            assert reply.status_code == 422 and "symbolic link" in reply.json()["detail"], reply.text
    # The race was real: some reads met the link (and were refused), most the file.
    assert statuses.get(422, 0) >= LINKS_SEEN and statuses.get(200, 0) > 0, statuses


def test_hostile_a_file_swapped_for_a_link_is_never_zipped_through_it(swapping: TestClient) -> None:
    client = swapping
    held = 0
    for _ in range(40):
        reply = client.get("/api/workspace/archive")
        assert reply.status_code == 200, reply.text
        with zipfile.ZipFile(io.BytesIO(reply.content)) as archive:
            contents = {name: archive.read(name) for name in archive.namelist()}
        assert all(b"TOPSECRET" not in data for data in contents.values()), "the secret was zipped"
        assert contents["src/pkg/steady.py"] == b"steady = 1\n"
        if "src/pkg/swap.py" in contents:
            assert contents["src/pkg/swap.py"] == REAL.encode()
            held += 1
    assert held > 0  # the file itself is zipped when it is a file


def nest(top: Path, count: int) -> Path:
    """``count`` folders ``d`` one inside the other under ``top``, made one at a time (no path
    as long as all of them is ever used); the deepest, as a path to write through an open fd."""
    fd = os.open(top, os.O_RDONLY | os.O_DIRECTORY)
    try:
        for _ in range(count):
            os.mkdir("d", dir_fd=fd)
            below = os.open("d", os.O_RDONLY | os.O_DIRECTORY, dir_fd=fd)
            os.close(fd)
            fd = below
        with open(os.open("bottom.py", os.O_WRONLY | os.O_CREAT, 0o644, dir_fd=fd), "w") as bottom:
            bottom.write("deep = 1\n")
    finally:
        os.close(fd)
    return top / "d"


def unnest(top: Path) -> None:
    """Remove a nest under ``top`` one level at a time, whatever the test did to it: pytest's own
    clean-up of old temporary folders recurses, and would fail on it (in a later run)."""
    deep, up = top / "d", top / "up"
    while deep.is_dir() and not deep.is_symlink():
        deep.rename(up)
        if (up / "d").is_dir() and not (up / "d").is_symlink():
            (up / "d").rename(deep)
        shutil.rmtree(up)


@pytest.fixture
def nests() -> Iterator[list[Path]]:
    """The folders a test nests folders in (``nest``); each is un-nested at the end."""
    tops: list[Path] = []
    try:
        yield tops
    finally:
        for top in tops:
            unnest(top)


def too_deep_example() -> str:
    return "/".join(["d"] * (DEPTH + 1))


def test_hostile_folders_nested_past_recursion_are_listed_zipped_saved_beside_and_removed(
    places: tuple[Path, Path], nests: list[Path]
) -> None:
    workspace, other = places
    nests.append(workspace)
    nest(workspace, NESTED)
    (workspace / "d" / "shallow.py").write_text("shallow = 1\n")
    (workspace / "d" / "d" / "out").symlink_to(other.parent, target_is_directory=True)
    with lab_client(lab_settings(workspace)) as client:
        listed = tree(client)
        assert listed["too_deep"] == 1 and listed["too_deep_example"] == too_deep_example()
        paths = [e["path"] for e in listed["entries"]]
        assert "d/shallow.py" in paths and "/".join(["d"] * DEPTH) in paths
        assert max(len(p.split("/")) for p in paths) == DEPTH
        archive = client.get("/api/workspace/archive")
        assert archive.status_code == 200 and names_in(archive.content) == ["d/shallow.py"]
        assert save(client, "d/d/new.py", "new = 1\n").status_code == 201
        removed = client.delete(f"{FILES}/d")
        assert removed.status_code == 200, removed.text
        assert removed.json() == {"path": "d", "deleted": 4}  # shallow, new, the link, bottom
        assert not (workspace / "d").exists()
        assert other.read_text() == SECRET  # the link went, not what it led to
        assert tree(client)["too_deep"] == 0


def test_hostile_the_depth_limit_is_the_settings(tmp_path: Path) -> None:
    with lab_client(lab_settings(tmp_path, files={"max_depth": 3})) as client:
        assert save(client, "a/b/c.py", "c = 1\n").status_code == 201
        deeper = save(client, "a/b/c/d.py", "d = 1\n")
        assert deeper.status_code == 422 and "deeper than 3" in deeper.json()["detail"]
        (tmp_path / "a" / "b" / "c2").mkdir()
        (tmp_path / "a" / "b" / "c2" / "d.py").write_text("d = 1\n")
        listed = tree(client)
        assert [e["path"] for e in listed["entries"]] == ["a", "a/b", "a/b/c.py", "a/b/c2"]
        assert listed["too_deep"] == 1 and listed["too_deep_example"] == "a/b/c2/d.py"


def test_hostile_the_instructor_reads_zips_and_removes_a_workspace_nested_past_recursion(
    tmp_path: Path, nests: list[Path]
) -> None:
    folder = tmp_path / "workspaces"
    nests.append(folder / "ada")
    settings = class_settings(workspaces_dir=folder, world={"writes_hz": 1000.0, "writes_burst": 1000})
    with TestClient(create_app(settings, ManualClock(1_000.0))) as client:
        token = join(client, "Ada")
        assert save(client, "src/a.py", "a = 1\n", **auth(token)).status_code == 201
        nest(folder / "ada", NESTED)
        teacher = auth(client.app.state.classroom.instructor_token)  # type: ignore[attr-defined]
        route = "/api/classroom/worlds/ada/workspace/files"
        listed = client.get(route, headers=teacher)
        assert listed.status_code == 200, listed.text
        assert listed.json()["too_deep"] == 1 and listed.json()["too_deep_example"] == too_deep_example()
        read = client.get(f"{route}/src/a.py", headers=teacher)
        assert read.status_code == 200 and read.json()["text"] == "a = 1\n"
        everyone = client.get("/api/classroom/workspaces/archive", headers=teacher)
        assert everyone.status_code == 200 and names_in(everyone.content) == ["ada/src/a.py"]
        own = client.get("/api/workspace/archive", headers=auth(token))
        assert own.status_code == 200 and names_in(own.content) == ["src/a.py"]
        removed = client.delete("/api/classroom/worlds/ada", headers=teacher)  # the workspace goes too
        assert removed.status_code == 200 and not (folder / "ada").exists()


def test_hostile_an_ordinary_upload_still_writes(places: tuple[Path, Path]) -> None:
    workspace, _ = places
    with lab_client(lab_settings(workspace)) as client:
        reply = upload(client, zip_of({"src/pkg/a.py": "a = 1\n", "src/other/b.py": "b = 2\n"}))
        assert reply.status_code == 200 and reply.json() == {"written": ["src/other/b.py", "src/pkg/a.py"]}
        assert (workspace / "src/other/b.py").read_text() == "b = 2\n"
