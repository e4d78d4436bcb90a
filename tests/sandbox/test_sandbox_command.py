"""The sandbox's command line, read without running it: what it binds, how, and the environment it
passes (tests/sandbox/test_sandbox.py runs it against a live class server)."""

from __future__ import annotations

from pathlib import Path

import pytest

from node_runtime.process.confinement import LIMITS_ENV, Confinement
from node_runtime.transport.acl import Credentials
from server.host.processes.command import RUNNER_MODULE, node_command
from server.host.processes.sandbox import INSIDE_ROUTER, PROJECT, SECCOMP_FD, SETPRIV, SOCKET_DIR, Sandbox


def binds(argv: list[str], kind: str) -> dict[str, str]:
    """``--bind``/``--ro-bind`` SRC DEST pairs of bwrap's argv (its own options only)."""
    own = argv[: argv.index("--")]
    return {own[i + 2]: own[i + 1] for i, arg in enumerate(own) if arg == kind}


@pytest.fixture
def wrapped(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> tuple[list[str], dict[str, str], Path]:
    monkeypatch.setenv("ROS2LAB_SERVER_SECRET", "not for students")
    monkeypatch.setattr("server.host.processes.sandbox.shutil.which", lambda _name: "/usr/bin/bwrap")
    monkeypatch.setattr("server.host.processes.sandbox.os.geteuid", lambda: 1000)  # as a non-root server
    workspace = tmp_path / "workspace"
    (workspace / "src" / "mine").mkdir(parents=True)
    node = workspace / "src" / "mine" / "node.py"
    node.write_text("print('hi')\n")
    socket = tmp_path / "router" / "router.sock"
    command = node_command(
        node,
        [],
        router=INSIDE_ROUTER,
        env={},
        login=Credentials("world-1", "pw"),
        domain_id=3,
        workspace=workspace,
    )
    out = Sandbox(socket, Confinement()).wrap(command, workspace)
    assert out.sandboxed and out.zid == command.zid
    return out.argv, out.env, workspace


def test_sandbox_command_binds_the_workspace_and_the_code_read_only(
    wrapped: tuple[list[str], dict[str, str], Path],
) -> None:
    argv, _env, workspace = wrapped
    read_write, read_only = binds(argv, "--bind"), binds(argv, "--ro-bind")
    assert read_write == {} and read_only[str(workspace)] == str(workspace)
    assert read_only[SOCKET_DIR] == str(workspace.parent / "router")
    assert {str(PROJECT / name) for name in ("server", "sim", "client")} <= set(read_only)
    assert str(PROJECT) not in read_only and str(PROJECT / "tests") not in read_only
    for namespace in ("--unshare-user", "--unshare-pid", "--unshare-net", "--unshare-ipc", "--unshare-uts"):
        assert namespace in argv
    assert argv[argv.index("--uid") + 1] != "0"
    assert argv[argv.index("--seccomp") + 1] == SECCOMP_FD  # the filter's descriptor, made at the start
    inside = argv[argv.index("--") + 1 :]
    assert (
        inside[1:3] == ["-I", "-B"] and RUNNER_MODULE in inside
    )  # isolated: no folder of the student's first


def test_sandbox_command_as_root_drops_every_capability_and_becomes_the_worlds_uid(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr("server.host.processes.sandbox.shutil.which", lambda _name: "/usr/bin/bwrap")
    monkeypatch.setattr("server.host.processes.sandbox.os.geteuid", lambda: 0)
    (tmp_path / "ws").mkdir()
    command = node_command(
        tmp_path / "ws" / "n.py", [], router=INSIDE_ROUTER, env={}, domain_id=4, workspace=tmp_path / "ws"
    )
    argv = Sandbox(tmp_path / "router.sock", Confinement()).wrap(command, tmp_path / "ws").argv
    own, inside = argv[: argv.index("--")], argv[argv.index("--") + 1 :]
    assert own[own.index("--cap-drop") + 1] == "ALL" and "--unshare-user" not in own
    assert inside[0] == SETPRIV and inside[inside.index("--reuid") + 1] == str(Confinement().uid + 4)
    assert {"--clear-groups", "--no-new-privs"} <= set(inside[: inside.index("--")])


def test_sandbox_command_environment_is_only_what_a_node_needs(
    wrapped: tuple[list[str], dict[str, str], Path],
) -> None:
    _argv, env, workspace = wrapped
    assert "ROS2LAB_SERVER_SECRET" not in env and "ROS2LAB_PARENT_PID" not in env
    assert set(env) == {
        "PYTHONUNBUFFERED",
        "PYTHONDONTWRITEBYTECODE",
        "ROS_DOMAIN_ID",
        "ZENOH_CONFIG_OVERRIDE",
        "ROS2LAB_WORKSPACE",
        "PATH",
        "HOME",
        "TMPDIR",
        "LANG",
        LIMITS_ENV,
    }
    assert env["ROS_DOMAIN_ID"] == "3" and env["ROS2LAB_WORKSPACE"] == str(workspace.resolve())
    assert f'connect/endpoints=["{INSIDE_ROUTER}"]' in env["ZENOH_CONFIG_OVERRIDE"]
    assert "world-1" in env["ZENOH_CONFIG_OVERRIDE"]  # its world's login, nothing of the class's


def test_confinement_round_trips_through_its_variable() -> None:
    limits = Confinement(memory_mib=300, processes=20, open_files=100, file_size_mib=5, cpu_s=9, nice=4)
    assert Confinement.decode(limits.encode()) == limits
    counted = limits.counting_address_space()
    assert Confinement.decode(counted.encode()) == counted and counted.address_space_mib > 300


def test_confinement_of_each_world_is_a_uid_of_its_own() -> None:
    base = Confinement()
    assert (base.for_domain(3).uid, base.for_domain(3).gid) == (base.uid + 3, base.gid + 3)
    assert base.for_domain(3).uid != base.for_domain(4).uid != 0
