"""A node's control group (server/host/processes/cgroups.py): where it is found from the process's
own groups and the mounts, what a new group is given, and how an OOM kill is read. The kernel's
side (a node over its limit ended) is tests/sandbox/test_sandbox.py's, on a live class server."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from server.host.processes.cgroups import (
    CPU_SHARES,
    CPU_WEIGHT,
    JOIN_SCRIPT,
    CgroupParent,
    NodeCgroup,
    _cpu_group_version_1,
    _delegate_version_2,
    _folder,
    _idle,
)


def test_cgroups_folder_is_the_group_below_its_mounts_root() -> None:
    assert _folder("/", "/sys/fs/cgroup/memory", "/class/a") == Path("/sys/fs/cgroup/memory/class/a")
    assert _folder("/docker/x", "/sys/fs/cgroup", "/docker/x/inner") == Path("/sys/fs/cgroup/inner")
    assert _folder("/docker/x", "/sys/fs/cgroup", "/docker/x") == Path("/sys/fs/cgroup")
    assert _folder("/docker/x", "/sys/fs/cgroup", "/elsewhere") is None  # not reachable through it


def test_cgroups_version_2_group_gets_memory_and_pids_limits(tmp_path: Path) -> None:
    group = CgroupParent(tmp_path, tmp_path, 2).make("node-1", memory_mib=512, processes=65)
    (folder,) = group.folders
    assert (folder / "memory.max").read_text() == str(512 * 1024 * 1024)
    assert (folder / "pids.max").read_text() == "65"
    assert group.oom_kills() == 0
    (folder / "memory.events").write_text("low 0\nhigh 0\nmax 3\noom 1\noom_kill 1\n")
    assert group.oom_kills() == 1


def test_cgroups_version_1_group_has_a_folder_in_each_hierarchy(tmp_path: Path) -> None:
    (tmp_path / "memory").mkdir()
    (tmp_path / "pids").mkdir()
    group = CgroupParent(tmp_path / "memory", tmp_path / "pids", 1).make(
        "node-2", memory_mib=64, processes=20
    )
    memory, pids = group.folders
    assert (memory / "memory.limit_in_bytes").read_text() == str(64 * 1024 * 1024)
    assert (pids / "pids.max").read_text() == "20"
    (memory / "memory.oom_control").write_text("oom_kill_disable 0\nunder_oom 0\noom_kill 2\n")
    assert group.oom_kills() == 2


def test_cgroups_join_prefix_writes_the_shells_pid_into_each_group_then_runs_the_command(
    tmp_path: Path,
) -> None:
    import subprocess

    group = NodeCgroup((tmp_path / "a", tmp_path / "b"), 1)
    for folder in group.folders:
        folder.mkdir()
    done = subprocess.run(
        [*group.join_prefix(), "/bin/sh", "-c", "echo ran $$"], capture_output=True, text=True, check=True
    )
    pid = done.stdout.split()[1]  # exec: the command is the shell that joined
    assert [(f / "cgroup.procs").read_text().strip() for f in group.folders] == [pid, pid]
    assert "exit 125" in JOIN_SCRIPT  # a group that refuses the pid stops the start


def test_cgroups_a_group_the_kernel_refuses_halfway_is_not_left_behind(tmp_path: Path) -> None:
    (tmp_path / "memory").mkdir()  # no pids folder: its group cannot be made
    parent = CgroupParent(tmp_path / "memory", tmp_path / "pids", 1)
    with pytest.raises(OSError):
        parent.make("node-3", memory_mib=64, processes=20)
    assert not (tmp_path / "memory" / "node-3").exists()


def test_cgroups_version_1_nodes_join_the_servers_one_cpu_group_and_leave_it_standing(tmp_path: Path) -> None:
    for name in ("memory", "pids", "cpu"):
        (tmp_path / name).mkdir()
    stale = tmp_path / "cpu" / "ros2lab-999999999"  # a server long gone (no such pid)
    stale.mkdir()
    cpu = _cpu_group_version_1(tmp_path / "cpu")
    assert cpu == tmp_path / "cpu" / f"ros2lab-{os.getpid()}" and not stale.exists()
    assert (cpu / "cpu.shares").read_text() == str(CPU_SHARES)
    parent = CgroupParent(tmp_path / "memory", tmp_path / "pids", 1, cpu, True)
    group = parent.make("node-4", memory_mib=64, processes=20)
    assert group.shared == (cpu,)
    procs = [arg for arg in group.join_prefix() if arg.endswith("cgroup.procs")]
    assert procs == [str(f / "cgroup.procs") for f in (*group.folders, cpu)]
    for file in [*cpu.iterdir(), *(p for f in group.folders for p in f.iterdir())]:
        file.unlink()  # empty, as the kernel's folders are to rmdir
    group.remove()
    assert not any(f.exists() for f in group.folders) and cpu.is_dir()  # the others' group stays


def test_cgroups_version_1_cpu_group_refused_is_none_and_not_left(tmp_path: Path) -> None:
    (tmp_path / f"ros2lab-{os.getpid()}").mkdir()
    (tmp_path / f"ros2lab-{os.getpid()}" / "cpu.shares").mkdir()  # a file the kernel would refuse
    assert _cpu_group_version_1(tmp_path) is None


def test_cgroups_version_2_weighs_the_nodes_folder_where_cpu_is_given(tmp_path: Path) -> None:
    nodes, weighed = _delegate_version_2(tmp_path)
    assert weighed and (nodes / "cpu.weight").read_text() == str(CPU_WEIGHT)
    assert (tmp_path / "cgroup.subtree_control").read_text() == "+cpu"  # after "+memory +pids"
    refused = tmp_path / "refused"
    refused.mkdir()
    (refused / f"ros2lab-{os.getpid()}").mkdir()
    (refused / f"ros2lab-{os.getpid()}" / "cpu.weight").mkdir()
    assert _delegate_version_2(refused) == (refused / f"ros2lab-{os.getpid()}", False)


def test_cgroups_the_nodes_cpu_group_is_made_idle_where_the_kernel_has_cpu_idle(tmp_path: Path) -> None:
    """The group is made idle where its folder takes ``cpu.idle``; where the kernel has none (older
    than 5.15) or refuses it, the group counts by its weight alone (the weight test: test_node_cpu_group)."""
    assert _idle(tmp_path) and (tmp_path / "cpu.idle").read_text() == "1"
    (tmp_path / "old" / "cpu.idle").mkdir(parents=True)  # a file the kernel would refuse
    assert not _idle(tmp_path / "old")
