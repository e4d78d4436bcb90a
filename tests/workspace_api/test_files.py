"""The workspace's files over REST on a single lab: the tree and its version, reading and saving
with versions (a save from a stale version is refused, and so is a second create), deleting,
renaming, new packages as ``ros2lab pkg create`` makes them, the templates, and the zip."""

from __future__ import annotations

import os
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from support.forked_cli import cli_command

from server.packages.templates import PackageSpec, package_files
from server.services.workspace.templates import TEMPLATES

from .helpers import FILES, lab_client, lab_settings, names_in, save, tree, upload, zip_of

NODE = "print('hello')\n"


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("files") / "workspace"


@pytest.fixture(scope="module")
def client(workspace: Path) -> Iterator[TestClient]:
    with lab_client(lab_settings(workspace)) as test_client:
        yield test_client


def test_files_a_new_file_is_created_read_and_listed(client: TestClient, workspace: Path) -> None:
    before = tree(client)
    created = save(client, "src/demo/demo/first.py", NODE, **{"If-None-Match": "*"})
    assert created.status_code == 201, created.text
    body = created.json()
    assert body["path"] == "src/demo/demo/first.py" and body["size"] == len(NODE)
    assert (workspace / "src/demo/demo/first.py").read_text() == NODE
    read = client.get(f"{FILES}/src/demo/demo/first.py")
    assert read.status_code == 200
    assert read.json() == {"path": "src/demo/demo/first.py", "text": NODE, "etag": body["etag"]}
    assert read.headers["etag"].strip('"') == body["etag"]
    after = tree(client)
    assert after["version"] != before["version"]
    listed = {e["path"]: e for e in after["entries"]}
    entry = {"path": "src/demo/demo/first.py", "kind": "file", "size": len(NODE), "etag": body["etag"]}
    assert listed["src/demo/demo/first.py"] == entry
    assert listed["src/demo"]["kind"] == "dir" and listed["src/demo"]["etag"] is None
    assert [e["path"] for e in after["entries"]] == sorted(listed)


def test_files_two_saves_from_one_version_the_second_is_412(client: TestClient) -> None:
    etag = save(client, "src/demo/demo/shared.py", "v1\n").json()["etag"]
    first = save(client, "src/demo/demo/shared.py", "from tab one\n", **{"If-Match": etag})
    assert first.status_code == 200, first.text
    second = save(client, "src/demo/demo/shared.py", "from tab two\n", **{"If-Match": f'"{etag}"'})
    assert second.status_code == 412
    assert second.json()["etag"] == first.json()["etag"] and "changed" in second.json()["detail"]
    assert client.get(f"{FILES}/src/demo/demo/shared.py").json()["text"] == "from tab one\n"
    again = save(client, "src/demo/demo/shared.py", "from tab two\n", **{"If-Match": second.json()["etag"]})
    assert again.status_code == 200  # the choice the page offers: overwrite the version it now knows


def test_files_create_only_refuses_an_existing_file(client: TestClient) -> None:
    save(client, "src/demo/demo/once.py", "mine\n")
    refused = save(client, "src/demo/demo/once.py", "theirs\n", **{"If-None-Match": "*"})
    assert refused.status_code == 412 and refused.json()["etag"] is not None
    assert client.get(f"{FILES}/src/demo/demo/once.py").json()["text"] == "mine\n"


def test_files_a_change_on_disk_changes_the_version_and_the_etag(client: TestClient, workspace: Path) -> None:
    etag = save(client, "src/demo/demo/edited.py", "a = 1\n").json()["etag"]
    version = tree(client)["version"]
    path = workspace / "src/demo/demo/edited.py"
    path.write_text("a = 2\n")  # a terminal user's editor, same size
    os.utime(path, ns=(path.stat().st_atime_ns, path.stat().st_mtime_ns + 1_000_000))
    assert tree(client)["version"] != version
    read = client.get(f"{FILES}/src/demo/demo/edited.py").json()
    assert read["text"] == "a = 2\n" and read["etag"] != etag
    assert save(client, "src/demo/demo/edited.py", "a = 3\n", **{"If-Match": etag}).status_code == 412
    version = tree(client)["version"]
    (workspace / "src/demo/demo/new_on_disk.py").write_text("")
    assert tree(client)["version"] != version


def test_files_delete_a_file_and_a_folder(client: TestClient, workspace: Path) -> None:
    etag = save(client, "src/gone/a.py", "a\n").json()["etag"]
    save(client, "src/gone/sub/b.py", "b\n")
    stale = client.delete(f"{FILES}/src/gone/a.py", headers={"If-Match": "not-its-version"})
    assert stale.status_code == 412 and (workspace / "src/gone/a.py").exists()
    deleted = client.delete(f"{FILES}/src/gone/a.py", headers={"If-Match": etag})
    assert deleted.json() == {"path": "src/gone/a.py", "deleted": 1}
    save(client, "src/gone/c.py", "c\n")
    assert client.delete(f"{FILES}/src/gone").json() == {"path": "src/gone", "deleted": 2}
    assert not (workspace / "src/gone").exists()
    assert client.delete(f"{FILES}/src/gone").status_code == 404
    assert client.get(f"{FILES}/src/gone/c.py").status_code == 404


def test_files_rename_moves_and_refuses_a_taken_target(client: TestClient, workspace: Path) -> None:
    save(client, "src/moving/old.py", "x\n")
    save(client, "src/moving/taken.py", "y\n")
    taken = client.post(
        "/api/workspace/rename", json={"source": "src/moving/old.py", "target": "src/moving/taken.py"}
    )
    assert taken.status_code == 409 and (workspace / "src/moving/old.py").exists()
    moved = client.post(
        "/api/workspace/rename", json={"source": "src/moving/old.py", "target": "src/moved/new.py"}
    )
    assert moved.status_code == 200 and moved.json() == {"path": "src/moved/new.py"}
    assert client.get(f"{FILES}/src/moved/new.py").json()["text"] == "x\n"
    assert client.get(f"{FILES}/src/moving/old.py").status_code == 404
    missing = client.post("/api/workspace/rename", json={"source": "src/nothing.py", "target": "src/x.py"})
    assert missing.status_code == 404
    extra = client.post(
        "/api/workspace/rename", json={"source": "src/moved/new.py", "target": "a.py", "force": True}
    )
    assert extra.status_code == 422  # strict bodies: an unknown field is refused


def test_files_new_package_writes_what_ros2lab_pkg_create_writes(
    client: TestClient, workspace: Path, tmp_path: Path
) -> None:
    body = {
        "name": "simple_control",
        "build_type": "ament_python",
        "node_name": "keyboard_manager",
        "dependencies": ["rclpy"],
        "description": None,
        "license": None,
    }
    created = client.post("/api/workspace/packages", json=body)
    assert created.status_code == 201, created.text
    spec = PackageSpec("simple_control", "ament_python", dependencies=["rclpy"], node_name="keyboard_manager")
    expected = sorted(f"src/simple_control/{p}" for p in package_files(spec))
    assert created.json()["name"] == "simple_control" and created.json()["path"] == "src/simple_control"
    assert sorted(created.json()["files"]) == expected
    cli = subprocess.run(
        cli_command(
            "pkg",
            "create",
            "simple_control",
            "--build-type",
            "ament_python",
            "--node-name",
            "keyboard_manager",
            "--dependencies",
            "rclpy",
            "--maintainer-name",
            "student",
            "--maintainer-email",
            "student@todo.todo",
        ),
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    )
    assert "creating" in cli.stdout
    for path in expected:
        relative = path.removeprefix("src/")
        assert (workspace / path).read_text() == (tmp_path / relative).read_text(), path
    again = client.post("/api/workspace/packages", json=body)
    assert again.status_code == 409
    bad = client.post("/api/workspace/packages", json={**body, "name": "Bad-Name"})
    assert bad.status_code == 422 and "Invalid package name" in bad.json()["detail"]
    assert not (workspace / "src/Bad-Name").exists()
    cmake = client.post(
        "/api/workspace/packages",
        json={"name": "cpp_pkg", "build_type": "ament_cmake", "node_name": None, "dependencies": []},
    )
    assert cmake.status_code == 201 and "src/cpp_pkg/CMakeLists.txt" in cmake.json()["files"]
    assert (workspace / "src/cpp_pkg/include/cpp_pkg").is_dir()


def test_files_templates_are_the_labs_skeletons(client: TestClient) -> None:
    reply = client.get("/api/workspace/templates")
    assert reply.status_code == 200
    templates = reply.json()
    assert [t["name"] for t in templates] == [t.name for t in TEMPLATES]
    for template in templates:
        assert set(template) == {"name", "title", "description", "path", "text"}
        assert "# TODO" in template["text"] or "<!-- TODO" in template["text"], template["name"]
        assert "{package}" in template["path"]
    for template in templates:
        if template["path"].endswith(".py"):
            compile(template["text"], template["name"], "exec")  # each skeleton is Python that runs


def test_files_archive_round_trip(client: TestClient, workspace: Path) -> None:
    save(client, "src/zipped/z.py", "z = 1\n")
    download = client.get("/api/workspace/archive")
    assert download.status_code == 200 and download.headers["content-type"] == "application/zip"
    names = names_in(download.content)
    assert "src/zipped/z.py" in names
    assert names == sorted(e["path"] for e in tree(client)["entries"] if e["kind"] == "file")
    written = upload(client, zip_of({"src/uploaded/u.py": "u = 1\n", "src/uploaded/launch/": b""}))
    assert written.status_code == 200, written.text
    assert written.json() == {"written": ["src/uploaded/u.py"]}
    assert (workspace / "src/uploaded/u.py").read_text() == "u = 1\n"


def test_files_a_lab_without_a_workspace_says_so() -> None:
    with lab_client(lab_settings(None)) as client:
        reply = client.get(FILES)
        assert reply.status_code == 404 and "no workspace" in reply.json()["detail"]


def test_files_a_file_larger_than_other_routes_bodies_is_saved(client: TestClient) -> None:
    """A workspace route takes bodies past the app's 64 KiB cap (a file up to 256 KiB); others do not."""
    text = "# long\n" * (200 * 1024 // 7)
    saved = save(client, "src/demo/demo/long.py", text)
    assert saved.status_code == 201, saved.text
    assert client.get(f"{FILES}/src/demo/demo/long.py").json()["text"] == text
    elsewhere = client.post(
        "/api/publish", json={"topic": "/long", "msg": {"data": text}, "type": "std_msgs/msg/String"}
    )
    assert elsewhere.status_code == 413


def test_files_an_upload_is_the_zips_bytes_whatever_its_type(client: TestClient, workspace: Path) -> None:
    data = zip_of({"src/typed/t.py": "t = 1\n"})
    reply = client.post(
        "/api/workspace/archive", content=data, headers={"content-type": "application/octet-stream"}
    )
    assert reply.status_code == 200 and reply.json() == {"written": ["src/typed/t.py"]}


def test_files_an_upload_with_replace_leaves_the_zips_files_only(tmp_path: Path) -> None:
    with lab_client(lab_settings(tmp_path)) as client:
        for path in ("src/a/b.py", "src/a/c.py", "src/keep/k.py", "src/d/e.py"):
            assert save(client, path, "old = 1\n").status_code == 201
        (tmp_path / ".hidden").write_text("not in the tree\n")
        before = tree(client)

        # Refused (one bad entry): nothing changes, nothing goes.
        bad = client.post(
            "/api/workspace/archive?replace=true",
            content=zip_of({"src/a/b.py": "new = 2\n", "../out.py": "x\n"}),
            headers={"content-type": "application/zip"},
        )
        assert bad.status_code == 422, bad.text
        assert tree(client) == before

        reply = client.post(
            "/api/workspace/archive?replace=true",
            content=zip_of({"src/a/b.py": "new = 2\n", "src/n/new.py": "n = 3\n", "src/d": "a file now\n"}),
            headers={"content-type": "application/zip"},
        )
        assert reply.status_code == 200, reply.text
        assert reply.json() == {"written": ["src/a/b.py", "src/d", "src/n/new.py"]}
        files = sorted(e["path"] for e in tree(client)["entries"] if e["kind"] == "file")
        assert files == ["src/a/b.py", "src/d", "src/n/new.py"]  # c.py, k.py and d/e.py went
        assert not (tmp_path / "src/keep").exists()  # the folder they left empty too
        assert (tmp_path / "src/a/b.py").read_text() == "new = 2\n"
        assert (tmp_path / "src/d").read_text() == "a file now\n"  # a file where a folder was
        assert (
            tmp_path / ".hidden"
        ).read_text() == "not in the tree\n"  # a name the tree does not list stays

        # Without replace the same upload adds and overwrites, and removes nothing.
        added = upload(client, zip_of({"src/z.py": "z = 4\n"}))
        assert added.status_code == 200
        assert {"src/a/b.py", "src/z.py"} <= {e["path"] for e in tree(client)["entries"]}


def test_files_a_replace_through_a_link_is_refused_before_anything_goes(tmp_path: Path) -> None:
    root, outside = tmp_path / "ws", tmp_path / "outside"
    outside.mkdir()
    with lab_client(lab_settings(root)) as client:
        assert save(client, "src/a/b.py", "old = 1\n").status_code == 201
        (root / "src/linked").symlink_to(outside, target_is_directory=True)
        before = tree(client)
        reply = client.post(
            "/api/workspace/archive?replace=true",
            content=zip_of({"src/linked/x.py": "x = 1\n"}),
            headers={"content-type": "application/zip"},
        )
        assert reply.status_code == 422, reply.text
        assert "symbolic link" in reply.json()["detail"]
        assert tree(client) == before and (root / "src/a/b.py").read_text() == "old = 1\n"  # nothing went
        assert list(outside.iterdir()) == []  # and nothing was written through the link
        # Without the link the same upload goes through.
        (root / "src/linked").unlink()
        assert client.post(
            "/api/workspace/archive?replace=true",
            content=zip_of({"src/linked/x.py": "x = 1\n"}),
            headers={"content-type": "application/zip"},
        ).json() == {"written": ["src/linked/x.py"]}
        assert not (root / "src/a/b.py").exists()
