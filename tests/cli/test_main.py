"""The CLI's entry points: ``python -m server <verb>``, ``ros2lab``, usage errors, no server."""

from __future__ import annotations

import ast
import os
import subprocess
import tomllib
from pathlib import Path

import pytest
from support.app import free_port

import server.__main__ as app_main
from server import cli

from .conftest import LiveServer, Result, cli_command

ROOT = Path(__file__).resolve().parents[2]


def run_cli(*args: str, env: dict[str, str] | None = None) -> Result:
    done = subprocess.run(
        cli_command(*args), capture_output=True, text=True, timeout=30, env=env, check=False
    )
    return Result(done.returncode, done.stdout, done.stderr)


def test_cli_against_a_dead_port_exits_2_with_one_line() -> None:
    url = f"http://127.0.0.1:{free_port()}"
    result = run_cli("topic", "list", "--url", url)
    assert result.code == 2
    assert result.out == ""
    assert result.err == f"error: no lab server at {url} (start it with: bash scripts/run.sh)\n"


def test_cli_echo_against_a_dead_port_exits_2_with_one_line() -> None:
    result = run_cli("topic", "echo", "/countdown", "--url", f"http://127.0.0.1:{free_port()}")
    assert result.code == 2
    assert len(result.err.splitlines()) == 1
    assert "no lab server at" in result.err


def test_cli_url_before_the_verb_and_from_the_environment(live_server: LiveServer) -> None:
    assert "/countdown" in run_cli("--url", live_server.url, "topic", "list").out.splitlines()
    env = {**os.environ, "TELEOP_URL": live_server.url}
    assert "/countdown" in run_cli("topic", "list", env=env).out.splitlines()


@pytest.mark.parametrize(
    "args",
    [
        ["topic"],
        ["topic", "nope"],
        ["topic", "pub", "/x"],
        ["topic", "pub", "-r", "0", "/x", "std_msgs/Bool"],
        ["node", "info"],
        ["launch"],
    ],
)
def test_cli_usage_error_exits_2(args: list[str]) -> None:
    with pytest.raises(SystemExit) as caught:
        cli.main(args)
    assert caught.value.code == 2


def test_app_main_dispatches_verbs_to_the_cli(monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[list[str]] = []

    def fake_main(argv: list[str]) -> int:
        seen.append(argv)
        return 0

    monkeypatch.setattr(cli, "main", fake_main)
    for verb in cli.VERBS:
        assert app_main.main([verb, "x"]) == 0
    assert seen == [[verb, "x"] for verb in cli.VERBS]


def test_app_parser_unchanged_for_server_options() -> None:
    args = app_main.build_parser().parse_args(["--port", "8001", "--launch", "rocket", "start_delay:=2.0"])
    assert (args.port, args.launch, args.launch_args) == (8001, "rocket", [("start_delay", "2.0")])


def test_console_script_ros2lab_points_at_cli_main() -> None:
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["ros2lab"] == "server.cli:main"
    assert scripts["teleop-lab"] == "server.__main__:main"


LOCAL_VERBS = {"run.py", "pkg.py", "pkg_create.py", "interface.py", "world_worker.py"}  # ``run`` starts the
# executable here, as ros2 run does, ``pkg`` reads and writes packages here, as ros2 pkg does, and
# ``interface`` reads the definitions here (the lab's and the workspace's), as ros2 interface does:
# they need the packages; ``world-worker`` hosts worlds itself.


# A reader of local files the CLI shares with node processes, importing nothing of the server:
# ``param set`` types a value and ``param load`` reads a parameters file as a node reads them.
SHARED_READERS = {"node_runtime.params_file"}


def test_cli_imports_nothing_of_the_server_it_talks_to() -> None:
    """The CLI reaches the lab only over the wire, so it works against any server it can reach;
    ``run`` alone starts something on this machine, and uses the package index and the runner."""
    for path in (ROOT / "server" / "cli").rglob("*.py"):
        if path.name in LOCAL_VERBS:
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            else:
                continue
            for name in set(names) - SHARED_READERS:
                if name == "server.cli" or name.startswith("server.cli."):
                    continue  # the CLI's own modules
                top = name.split(".")[0]
                assert top not in {"server", "node_runtime", "api", "sim", "fastapi", "uvicorn", "viser"}, (
                    path,
                    name,
                )


def test_cli_help_runs_without_a_server() -> None:
    result = run_cli("topic", "pub", "--help")
    assert result.code == 0
    assert "--rate" in result.out
