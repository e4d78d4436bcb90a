"""Bad input to the workspace is refused with a 4xx that names the problem, and changes nothing:
paths that leave the workspace (``..``, absolute, a backslash, a NUL, through a symbolic link),
files and workspaces over their limits, binary content, and zips that are bombs (by their declared
and by their real size), hold ``..``, absolute or symbolic-link entries, binary files or too many
entries. Each refusal is checked against the tree before and after, and each has a legitimate
counterpart that works, so a refusal cannot pass because the route is broken."""

from __future__ import annotations

import io
import stat
import struct
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from .helpers import FILES, lab_client, lab_settings, save, tree, upload, zip_of

MAX_FILE = 2048
MAX_TOTAL = 8000
MAX_FILES = 6
MAX_BODY = 128 * 1024  # above the app's 64 KiB for other routes


@pytest.fixture(scope="module")
def folders(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Path]:
    root = tmp_path_factory.mktemp("refusals")
    outside = root / "outside"
    outside.mkdir()
    (outside / "secret.txt").write_text("the server's own file\n")
    workspace = root / "workspace"
    (workspace / "src").mkdir(parents=True)
    (workspace / "src" / "link").symlink_to(outside, target_is_directory=True)
    return workspace, outside


@pytest.fixture(scope="module")
def client(folders: tuple[Path, Path]) -> Iterator[TestClient]:
    files = {
        "max_file_bytes": MAX_FILE,
        "max_workspace_bytes": MAX_TOTAL,
        "max_files": MAX_FILES,
        "max_body_bytes": MAX_BODY,
    }
    with lab_client(lab_settings(folders[0], files=files)) as test_client:
        save(test_client, "src/pkg/kept.py", "kept = True\n")
        yield test_client


@pytest.fixture
def unchanged(client: TestClient, folders: tuple[Path, Path]) -> Iterator[None]:
    """The workspace's tree and the folder outside it are the same after the test as before."""
    before, outside = tree(client), sorted(p.name for p in folders[1].iterdir())
    yield
    assert tree(client) == before
    assert sorted(p.name for p in folders[1].iterdir()) == outside
    assert not (folders[0].parent / "evil.py").exists()


def refused(reply: Any, status: int, words: str) -> None:
    assert reply.status_code == status, (reply.status_code, reply.text)
    assert words in str(reply.json()["detail"]), reply.json()


@pytest.mark.parametrize(
    ("path", "status", "words"),
    [
        ("%2e%2e/evil.py", 400, "path"),  # the app's path check, before any route
        ("src/%2e%2e/%2e%2e/evil.py", 400, "path"),
        ("/evil.py", 400, "path"),  # an absolute path makes an empty segment: //
        ("src%5cevil.py", 400, "path"),
        ("src/.hidden.py", 422, "not a name"),
        ("src/-rf.py", 422, "not a name"),
        ("src/with space.py", 422, "not a name"),
        ("src/link/evil.py", 422, "symbolic link"),
    ],
)
def test_refusals_a_path_out_is_refused(
    client: TestClient, unchanged: None, path: str, status: int, words: str
) -> None:
    refused(client.put(f"{FILES}/{path}", json={"text": "x\n"}), status, words)
    assert 400 <= client.get(f"{FILES}/{path}").status_code < 500
    assert 400 <= client.delete(f"{FILES}/{path}").status_code < 500


def test_refusals_a_file_through_a_link_is_not_read(client: TestClient, unchanged: None) -> None:
    refused(client.get(f"{FILES}/src/link/secret.txt"), 422, "symbolic link")
    assert "src/link" not in [e["path"] for e in tree(client)["entries"]]  # neither listed nor followed
    assert client.get(f"{FILES}/src/pkg/kept.py").json()["text"] == "kept = True\n"


@pytest.mark.parametrize(
    ("source", "target", "words"),
    [
        ("src/pkg/kept.py", "../evil.py", "'..'"),
        ("src/pkg/kept.py", "/evil.py", "absolute"),
        ("src/pkg/kept.py", "src\\evil.py", "backslash"),
        ("src/pkg/kept.py", "src/evil\x00.py", "NUL"),
        ("src/pkg/kept.py", "src/link/evil.py", "symbolic link"),
        ("../outside/secret.txt", "src/pkg/stolen.txt", "'..'"),
        ("src/pkg", "src/pkg/inside", "into itself"),
    ],
)
def test_refusals_a_rename_out_is_refused(
    client: TestClient, unchanged: None, source: str, target: str, words: str
) -> None:
    reply = client.post("/api/workspace/rename", json={"source": source, "target": target})
    assert 400 <= reply.status_code < 500 and words in reply.json()["detail"], reply.text


def test_refusals_a_save_under_a_file_is_409(client: TestClient, unchanged: None) -> None:
    refused(save(client, "src/pkg/kept.py/inner.py", "x\n"), 409, "is a file")


def test_refusals_a_rename_inside_works(client: TestClient) -> None:
    save(client, "src/pkg/to_move.py", "m\n")
    assert (
        client.post(
            "/api/workspace/rename", json={"source": "src/pkg/to_move.py", "target": "src/pkg/moved.py"}
        ).status_code
        == 200
    )
    assert client.delete(f"{FILES}/src/pkg/moved.py").status_code == 200


def test_refusals_an_oversized_file_is_413(client: TestClient, unchanged: None) -> None:
    refused(save(client, "src/pkg/big.py", "x" * (MAX_FILE + 1)), 413, f"limit of {MAX_FILE} per file")
    refused(
        save(client, "src/pkg/big.py", "é" * (MAX_FILE // 2 + 1)), 413, "per file"
    )  # bytes, not characters


def test_refusals_a_file_at_the_limit_is_saved(client: TestClient) -> None:
    assert save(client, "src/pkg/at_limit.py", "x" * MAX_FILE).status_code == 201
    assert client.delete(f"{FILES}/src/pkg/at_limit.py").status_code == 200


def test_refusals_a_body_over_the_routes_cap_is_413(client: TestClient, unchanged: None) -> None:
    reply = client.put(
        f"{FILES}/src/pkg/huge.py",
        content=b'{"text": "' + b"x" * MAX_BODY + b'"}',
        headers={"content-type": "application/json"},
    )
    refused(reply, 413, f"body larger than {MAX_BODY} bytes")


def test_refusals_a_full_workspace_takes_no_more(client: TestClient) -> None:
    paths = [f"src/fill/f{i}.py" for i in range(4)]
    for path in paths[:3]:
        assert save(client, path, "y" * 2000).status_code == 201
    before = tree(client)
    refused(save(client, paths[3], "y" * 2000), 413, "over its limit")  # 4 × 2000 + kept.py > 8000
    assert tree(client) == before
    for path in paths[:3]:
        assert client.delete(f"{FILES}/{path}").status_code == 200
    assert save(client, paths[3], "y" * 2000).status_code == 201  # room again
    assert client.delete(f"{FILES}/src/fill").status_code == 200


def test_refusals_too_many_files_is_413(client: TestClient) -> None:
    count = len([e for e in tree(client)["entries"] if e["kind"] == "file"])
    made = [f"src/many/m{i}.py" for i in range(MAX_FILES - count)]
    for path in made:
        assert save(client, path, "m\n").status_code == 201
    before = tree(client)
    refused(save(client, "src/many/one_more.py", "m\n"), 413, f"limit of {MAX_FILES}")
    assert tree(client) == before
    assert save(client, made[0], "overwriting is no new file\n").status_code == 200
    assert client.delete(f"{FILES}/src/many").status_code == 200


def test_refusals_binary_text_and_files_are_415(
    client: TestClient, folders: tuple[Path, Path], unchanged: None
) -> None:
    refused(save(client, "src/pkg/nul.py", "a\x00b"), 415, "NUL")
    lone_surrogate = client.put(
        f"{FILES}/src/pkg/surrogate.py",
        content=b'{"text": "\\ud800"}',
        headers={"content-type": "application/json"},
    )
    refused(lone_surrogate, 415, "not valid Unicode")


def test_refusals_a_binary_file_on_disk_is_not_read_as_text(
    client: TestClient, folders: tuple[Path, Path]
) -> None:
    (folders[0] / "src" / "pkg" / "image.png").write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    (folders[0] / "src" / "pkg" / "latin1.txt").write_bytes("café".encode("latin-1"))
    try:
        refused(client.get(f"{FILES}/src/pkg/image.png"), 415, "not a text file")
        refused(client.get(f"{FILES}/src/pkg/latin1.txt"), 415, "not UTF-8")
    finally:
        (folders[0] / "src" / "pkg" / "image.png").unlink()
        (folders[0] / "src" / "pkg" / "latin1.txt").unlink()


def symlink_entry(name: str, target: str) -> bytes:
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w") as archive:
        archive.writestr("src/pkg/fine.py", "fine = 1\n")
        info = zipfile.ZipInfo(name)
        info.external_attr = (stat.S_IFLNK | 0o777) << 16
        archive.writestr(info, target)
    return buffer.getvalue()


def lying_sizes(name: str, real: bytes, declared: int) -> bytes:
    """A zip whose entry says it inflates to ``declared`` bytes and really inflates to ``real``."""
    data = bytearray(zip_of({name: real}))
    for signature, offset in ((b"PK\x03\x04", 22), (b"PK\x01\x02", 24)):  # the local and the central header
        at = data.find(signature)
        struct.pack_into("<I", data, at + offset, declared)
    return bytes(data)


def duplicate_names() -> bytes:
    """A zip naming one path twice (zipfile only warns when it writes one)."""
    return zip_of({"src/pkg/d1.py": "first\n", "src/pkg/d2.py": "second\n"}).replace(b"d2.py", b"d1.py")


def deflated_zeros(count: int) -> bytes:
    return zip_of({"src/pkg/zeros.py": b" " * count})


@pytest.mark.parametrize(
    ("data", "status", "words"),
    [
        (b"not a zip at all", 422, "not a zip file"),
        (zip_of({"../evil.py": "x\n"}), 422, "'..'"),
        (zip_of({"src/pkg/fine.py": "fine\n", "src/../../evil.py": "x\n"}), 422, "'..'"),
        (zip_of({"/evil.py": "x\n"}), 422, "absolute"),
        (zip_of({"src\\evil.py": "x\n"}), 422, "backslash"),
        (zip_of({"src/.git/config": "x\n"}), 422, "not a name"),
        (symlink_entry("src/pkg/out", "../../outside/secret.txt"), 422, "symbolic link"),
        (zip_of({"src/pkg/fine.py": "fine\n", "src/pkg/blob.bin": b"\x00\x01\x02"}), 415, "NUL"),
        (zip_of({"src/pkg/latin.py": "café".encode("latin-1")}), 415, "not UTF-8"),
        (deflated_zeros(MAX_FILE + 1), 413, "declares"),  # a bomb by its header: small zip, big file
        (lying_sizes("src/pkg/bomb.py", b" " * 100_000, 100), 422, "cannot be read"),  # a header that lies
        (
            zip_of({f"src/pkg/f{i}.py": "y" * 1500 for i in range(6)}),
            413,
            "declare",
        ),  # together over the workspace
        (zip_of({f"src/pkg/n{i}.py": "" for i in range(MAX_FILES + 1)}), 413, "entries"),
        (zip_of({"src/pkg/kept.py/inner.py": "x\n"}), 422, "is a file"),  # a file where a folder would go
        (zip_of({"src/pkg/a.py": "x\n", "src/pkg/a.py/b.py": "y\n"}), 422, "a file and a folder"),
        (zip_of({"src/pkg/space.py": "x\n", "src/pkg/with space.py": "y\n"}), 422, "not a name"),
        (duplicate_names(), 422, "there twice"),
    ],
    ids=[
        "not-zip",
        "dotdot",
        "dotdot-among-good",
        "absolute",
        "backslash",
        "hidden",
        "symlink",
        "binary",
        "latin1",
        "bomb-declared",
        "bomb-real",
        "total",
        "too-many",
        "file-as-folder",
        "file-and-folder",
        "space",
        "twice",
    ],
)
def test_refusals_a_bad_zip_writes_nothing(
    client: TestClient, unchanged: None, data: bytes, status: int, words: str
) -> None:
    reply = upload(client, data)
    assert reply.status_code == status, reply.text
    assert words in str(reply.json()["detail"]), reply.json()


def test_refusals_a_real_size_past_the_limit_is_caught_while_reading(
    client: TestClient, unchanged: None
) -> None:
    """A header that claims a size under the limit for content past it: the reading stops there."""
    reply = upload(client, lying_sizes("src/pkg/bomb.py", b" " * (MAX_FILE * 50), MAX_FILE))
    assert 400 <= reply.status_code < 500 and reply.json()["detail"], reply.text


def test_refusals_a_good_zip_of_the_same_shape_is_written(
    client: TestClient, folders: tuple[Path, Path]
) -> None:
    reply = upload(client, zip_of({"src/pkg/fine.py": "fine\n", "src/pkg/launch/x.launch": "<launch/>\n"}))
    assert reply.status_code == 200, reply.text
    assert reply.json()["written"] == ["src/pkg/fine.py", "src/pkg/launch/x.launch"]
    assert (folders[0] / "src/pkg/fine.py").read_text() == "fine\n"
    assert client.delete(f"{FILES}/src/pkg/fine.py").status_code == 200
    assert client.delete(f"{FILES}/src/pkg/launch").status_code == 200


def test_refusals_another_sites_page_writes_nothing(client: TestClient, unchanged: None) -> None:
    foreign = {"Origin": "http://evil.example"}
    refused(save(client, "src/pkg/evil.py", "x\n", **foreign), 403, "cross-site")
    refused(upload(client, zip_of({"src/pkg/evil.py": "x\n"}), **foreign), 403, "cross-site")
    refused(client.delete(f"{FILES}/src/pkg/kept.py", headers=foreign), 403, "cross-site")
    refused(client.post("/api/workspace/packages", json={"name": "evil"}, headers=foreign), 403, "cross-site")


def test_refusals_the_labs_own_page_writes(client: TestClient) -> None:
    assert save(client, "src/pkg/own.py", "x\n", Origin="http://testserver").status_code == 201
    assert (
        client.delete(f"{FILES}/src/pkg/own.py", headers={"Origin": "http://testserver"}).status_code == 200
    )


def test_refusals_a_lab_behind_a_token_needs_it(tmp_path: Path) -> None:
    settings = lab_settings(tmp_path / "workspace")
    settings = settings.model_copy(
        update={"listen": settings.listen.model_copy(update={"token": "the-token"})}
    )
    with lab_client(settings) as client:
        refused(save(client, "src/pkg/a.py", "x\n"), 401, "token")
        refused(client.get(FILES), 401, "token")
        assert not (tmp_path / "workspace").exists()
        assert save(client, "src/pkg/a.py", "x\n", Authorization="Bearer the-token").status_code == 201
