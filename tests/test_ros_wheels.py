"""ROS 2's definitions from its wheels (node_runtime/ros_wheels.py): only the definitions and their hashes
come out of a wheel, a current folder is left alone, the cache is used only for the pinned hash,
and a download that fails says so. Wheels here are made in the test; pip is kept off the network
(no index, an empty folder of links)."""

from __future__ import annotations

import hashlib
import json
import os
import zipfile
from pathlib import Path

import pytest

from node_runtime import ros_wheels
from node_runtime.ros_wheels import SetUpError, ensure, read_lock

DATA = "ros_demo_msgs-1.2.3.data/data"


def make_wheel(folder: Path, name: str = "ros_demo_msgs-1.2.3-cp311-cp311-manylinux_2_28_x86_64.whl") -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    description = {"type_hashes": [{"type_name": "demo_msgs/msg/Ping", "hash_string": "RIHS01_" + "ab" * 32}]}
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr(f"{DATA}/share/demo_msgs/msg/Ping.msg", "uint32 seq\n")
        archive.writestr(f"{DATA}/share/demo_msgs/msg/Ping.json", json.dumps(description))
        archive.writestr(f"{DATA}/share/demo_msgs/msg/Ping.idl", "module demo_msgs {};\n")
        archive.writestr(f"{DATA}/share/demo_msgs/srv/Echo.srv", "string text\n---\nstring text\n")
        archive.writestr(f"{DATA}/share/demo_msgs/action/Count.action", "int32 n\n---\n---\n")
        archive.writestr(f"{DATA}/share/demo_msgs/cmake/demo_msgsConfig.cmake", "")
        archive.writestr(f"{DATA}/lib/python3.11/site-packages/demo_msgs/msg/_ping.py", "")
    return path


def lock_for(tmp_path: Path, wheel: Path, version: str = "1.2.3") -> Path:
    lock = tmp_path / "ros_packages.txt"
    digest = hashlib.sha256(wheel.read_bytes()).hexdigest()
    lock.write_text(f"# a comment\nros-demo-msgs=={version} --hash=sha256:{digest}\n", encoding="utf-8")
    return lock


def test_ros_wheels_extract_only_the_definitions_and_rosidls_hashes(tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    lock = lock_for(tmp_path, make_wheel(cache))
    target = tmp_path / "ros_interfaces"
    previous = os.umask(0o077)  # a user's restrictive umask
    try:
        said = ensure(lock, target, cache)
    finally:
        os.umask(previous)
    assert "0 downloaded, 1 from" in said and "3 files" in said
    files = {p.relative_to(target).as_posix() for p in target.rglob("*") if p.is_file()}
    assert files == {
        "demo_msgs/msg/Ping.msg",
        "demo_msgs/srv/Echo.srv",
        "demo_msgs/action/Count.action",
        ros_wheels.HASHES_FILE,
        ros_wheels.STAMP_FILE,
    }
    assert (target / "demo_msgs/msg/Ping.msg").read_text() == "uint32 seq\n"
    # Readable by every user (a sandboxed node runs as another), whatever the umask was.
    assert {p.stat().st_mode & 0o777 for p in [target, *target.rglob("*")] if p.is_dir()} == {0o755}
    assert {p.stat().st_mode & 0o777 for p in target.rglob("*") if p.is_file()} == {0o644}
    hashes = json.loads((target / ros_wheels.HASHES_FILE).read_text())
    assert hashes == {"demo_msgs/msg/Ping": "RIHS01_" + "ab" * 32}


def test_ros_wheels_a_current_folder_is_left_alone_and_a_new_lock_replaces_it(tmp_path: Path) -> None:
    cache = tmp_path / "cache"
    lock = lock_for(tmp_path, make_wheel(cache))
    target = tmp_path / "ros_interfaces"
    ensure(lock, target, cache)
    marker = target / "demo_msgs/msg/Marker.msg"
    marker.write_text("int8 x\n")
    assert ensure(lock, target, cache) == ""  # current: not even the cache is read
    assert marker.exists()
    lock.write_text(lock.read_text() + "# another comment\n")
    assert ensure(lock, target, cache) != ""
    assert not marker.exists() and (target / "demo_msgs/msg/Ping.msg").exists()


def test_ros_wheels_a_cached_file_with_another_hash_is_not_used(tmp_path: Path) -> None:
    wheel = make_wheel(tmp_path / "elsewhere")
    lock = lock_for(tmp_path, wheel)
    cache = tmp_path / "cache"
    cache.mkdir()
    (cache / wheel.name).write_bytes(b"not the pinned wheel")
    (pin,) = read_lock(lock.read_text())
    assert ros_wheels.cached_wheel(pin, cache) is None
    (cache / wheel.name).write_bytes(wheel.read_bytes())
    assert ros_wheels.cached_wheel(pin, cache) == cache / wheel.name


def test_ros_wheels_a_failed_download_says_what_could_not_be_had(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    lock = lock_for(tmp_path, make_wheel(tmp_path / "elsewhere"))
    (tmp_path / "no-links").mkdir()
    monkeypatch.setenv("PIP_NO_INDEX", "1")  # pip offline: nothing to find anywhere
    monkeypatch.setenv("PIP_FIND_LINKS", str(tmp_path / "no-links"))
    target = tmp_path / "ros_interfaces"
    with pytest.raises(
        SetUpError, match=r"could not download ROS 2's interface packages from PyPI \(ros-demo-msgs\)"
    ):
        ensure(lock, target, tmp_path / "cache")
    assert not target.exists()
    assert ros_wheels.main() == 0  # the lab's own folder is current: nothing to fetch


def test_ros_wheels_a_bad_lock_line_is_named() -> None:
    with pytest.raises(SetUpError, match=r"ros_packages.txt:2: expected 'name==version --hash=sha256:HEX'"):
        read_lock("# fine\nros-std-msgs>=5\n")


def test_ros_wheels_the_lock_pins_every_ros_package_the_lab_generates() -> None:
    pinned = {p.name.removeprefix("ros-").replace("-", "_") for p in read_lock(ros_wheels.LOCK.read_text())}
    # a package's folder (a ROS package name starts with a letter; __pycache__ holds the parse cache)
    extracted = {p.name for p in ros_wheels.TARGET.iterdir() if p.is_dir() and p.name[0].isalpha()}
    assert pinned == extracted
    assert {"std_msgs", "geometry_msgs", "sensor_msgs", "rcl_interfaces", "lifecycle_msgs"} <= pinned
