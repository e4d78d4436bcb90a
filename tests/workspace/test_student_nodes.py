"""Students' workspaces: their packages overlay the lab's, and their files are placed as processes.

These run on a ManualClock with no Zenoh: where a student's file goes, and what is said when it
cannot go there. The processes themselves are tested in tests/processes.
"""

from __future__ import annotations

import logging
import textwrap
from pathlib import Path

import pytest

from node_runtime.ament.index import ExecutableNotFoundError, NotInProcessError, PackageIndex
from node_runtime.bus import ManualClock
from server.host.settings import LabSettings, Settings
from server.world.lab import Lab

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "workspace"


def write_pkg(root: Path, pkg: str, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        path = root / "src" / pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return root


def test_workspace_overlay_keeps_builtin_executables_and_reports_unknown(tmp_path: Path) -> None:
    write_pkg(tmp_path, "rocketship", {"src/my_manager.py": "x = 1\n"})
    index = PackageIndex(workspace=tmp_path)
    exes = index.executables_of("rocketship")
    assert {"countdown", "main_controller", "my_manager.py", "my_manager"} <= set(exes)
    assert exes["my_manager.py"].file == tmp_path / "src" / "rocketship" / "src" / "my_manager.py"
    assert exes["countdown"].builtin is not None and exes["countdown"].file is None
    assert (
        index.share_dir("rocketship").name == "rocketship" and "server" in index.share_dir("rocketship").parts
    )
    with pytest.raises(ExecutableNotFoundError, match="no executable 'nope'"):
        index.resolve("rocketship", "nope")


def test_example_workspace_files_win_over_the_lab_nodes_of_the_same_name() -> None:
    index = PackageIndex(workspace=EXAMPLES)
    manager = index.resolve("rocketship", "keyboard_manager.py")
    assert manager.file == EXAMPLES / "src" / "rocketship" / "src" / "keyboard_manager.py"
    drone = index.resolve("simple_control", "keyboard_manager")
    assert drone.file is not None and drone.file.parent.name == "simple_control"
    with pytest.raises(NotInProcessError, match="runs as its own process"):
        index.factory("rocketship", "keyboard_manager.py")


def test_student_file_without_the_zenoh_graph_fails_to_start_saying_why_and_the_rest_runs(
    caplog: pytest.LogCaptureFixture,
) -> None:
    lab = Lab(Settings(lab=LabSettings(launch="rocket", viewer=False, workspace=EXAMPLES)), ManualClock(0.0))
    with caplog.at_level(logging.ERROR, logger="launch"):
        lab.start_nodes()
    entry = next(e for e in lab.launcher.launched if e.action.exec == "keyboard_manager.py")
    assert entry.node is None and entry.process is None
    assert entry.error is not None and "runs as its own process" in entry.error and "Zenoh" in entry.error
    assert "keyboard_manager.py" in caplog.text
    lab.executor.spin_until(20.0)
    assert lab.bus.topics["/countdown"].latest.data == 0  # the lab's nodes ran on


def test_all_processes_keeps_the_device_nodes_inside_the_app() -> None:
    lab = Lab(
        Settings(lab=LabSettings(launch="rocket", viewer=False, workspace=None, node_processes="all")),
        ManualClock(0.0),
    )
    index = lab.packages
    assert lab.launcher.runs_as_process(index.resolve("rocketship", "countdown"))
    assert not lab.launcher.runs_as_process(index.resolve("keyboard", "keyboard"))
    assert not lab.launcher.runs_as_process(index.resolve("visualizer", "gui_controller.py"))
