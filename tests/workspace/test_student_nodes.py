"""Students' node files: rclpy-style code from a workspace joins the running graph."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from server.bus import ManualClock
from server.lab import Lab
from server.msgs import Key
from server.packages import ExecutableNotFoundError, PackageIndex
from server.settings import Settings

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "workspace"


def make_lab(workspace: Path, launch: str = "rocket", **args: str) -> Lab:
    lab = Lab(Settings(launch=launch, viewer=False, workspace=workspace, launch_args=args), ManualClock(0.0))
    lab.start_nodes()
    return lab


def write_pkg(root: Path, pkg: str, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        path = root / "src" / pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return root


def test_example_keyboard_manager_overlay_replaces_builtin_and_aborts() -> None:
    lab = make_lab(EXAMPLES, start_delay="1.0")
    node = lab.bus.get_node("KeyboardManager")
    assert type(node).__module__.startswith("_lab_workspace_"), "the student's file, not the built-in node"
    lab.keyboard.key_down(Key.KEY_A, 0, "test")
    lab.executor.spin_until(15.0)
    assert lab.bus.topics["/abort_takeoff"].latest.data is True
    assert "/cmd_vel" not in lab.bus.topics or lab.bus.topics["/cmd_vel"].publish_count == 0


def test_example_drone_manager_runs_with_its_sleep_skipped(caplog: pytest.LogCaptureFixture) -> None:
    lab = make_lab(EXAMPLES)  # the rocket launch: its keyboard node, and no other drone manager
    group = lab.run_node("simple_control", "keyboard_manager", name="my_manager")
    assert [n["error"] for n in group.describe()["nodes"]] == [None]
    assert "time.sleep(10) skipped" in caplog.text
    lab.executor.spin_until(1.0)
    lab.keyboard.key_down(Key.KEY_RIGHT, 0, "test")
    lab.executor.spin_until(1.2)
    mine = [p for p in lab.bus.topics["/uav/input/position"].publishers if p.node.get_name() == "my_manager"]
    assert len(mine) == 1
    assert lab.bus.topics["/uav/input/position"].latest.x == 1.0


def test_student_node_file_joins_graph_with_its_topics(tmp_path: Path) -> None:
    write_pkg(
        tmp_path,
        "my_pkg",
        {
            "my_pkg/talker.py": """
        import rclpy
        from rclpy.node import Node
        from std_msgs.msg import String

        class Talker(Node):
            def __init__(self):
                super().__init__('talker')
                self.pub = self.create_publisher(String, 'chatter', 10)
                self.create_timer(0.5, lambda: self.pub.publish(String(data='hello')))
        """
        },
    )
    lab = make_lab(tmp_path)
    group = lab.run_node("my_pkg", "talker")
    lab.executor.spin_until(2.0)
    assert group.describe()["nodes"][0]["name"] == "/talker"
    topic = lab.bus.topics["/chatter"]
    assert topic.publish_count == 4 and topic.latest.data == "hello"
    lab.stop_group(group.id)
    assert "/chatter" not in lab.bus.topics, "no stale topic after the node is stopped"


def test_student_node_that_raises_in_a_callback_is_crashed_and_others_run(tmp_path: Path) -> None:
    write_pkg(
        tmp_path,
        "my_pkg",
        {
            "bad.py": """
        from rclpy.node import Node

        class Bad(Node):
            def __init__(self):
                super().__init__('bad')
                self.create_timer(0.1, self.tick)

            def tick(self):
                raise ZeroDivisionError('oops')
        """
        },
    )
    lab = make_lab(tmp_path, start_delay="0")
    lab.run_node("my_pkg", "bad.py")
    lab.executor.spin_until(3.0)
    bad = lab.bus.get_node("bad")
    assert bad.state == "crashed" and "ZeroDivisionError" in (bad.crash_reason or "")
    assert lab.bus.topics["/countdown"].publish_count == 4, "the rocket's countdown ran on"


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        ("x = (\n", "bad.py:1: SyntaxError"),
        ("import no_such_module_here\n", "bad.py:1: ModuleNotFoundError"),
        (
            "from rclpy.node import Node\nclass A(Node):\n    def __init__(self):\n"
            "        super().__init__('a')\n        raise RuntimeError('no')\n",
            "bad.py:5: A() raised RuntimeError: no",
        ),
        ("x = 1\n", "exactly one Node subclass (found: none)"),
    ],
)
def test_student_node_that_fails_to_load_names_file_and_line(
    tmp_path: Path, source: str, expected: str
) -> None:
    write_pkg(tmp_path, "my_pkg", {"bad.py": source})
    lab = make_lab(tmp_path, start_delay="0")
    before = {n.fully_qualified_name for n in lab.bus.nodes}
    group = lab.run_node("my_pkg", "bad.py")
    error = group.describe()["nodes"][0]["error"]
    assert error is not None and expected in error
    assert {n.fully_qualified_name for n in lab.bus.nodes} == before, "nothing half-built stays in the graph"
    lab.executor.spin_until(2.0)
    assert lab.bus.topics["/countdown"].publish_count == 3


def test_student_node_with_respawn_restarts_after_crash(tmp_path: Path) -> None:
    write_pkg(
        tmp_path,
        "my_pkg",
        {
            "flaky.py": """
            from rclpy.node import Node

            class Flaky(Node):
                def __init__(self):
                    super().__init__('flaky')
                    self.create_timer(1.0, self.tick)

                def tick(self):
                    raise RuntimeError('crash every second')
            """,
            "launch/flaky.launch": """
            <launch>
              <node pkg="my_pkg" exec="flaky" name="flaky" respawn="true" respawn_delay="0.5"/>
            </launch>
            """,
        },
    )
    lab = make_lab(tmp_path)
    lab.launch_group(lab.packages.share_dir("my_pkg") / "launch" / "flaky.launch", {})
    entry = next(e for e in lab.launcher.launched if e.action.exec == "flaky")
    lab.executor.spin_until(1.2)
    assert lab.bus.get_node("flaky").state == "crashed"
    lab.executor.spin_until(1.8)
    assert entry.starts == 2 and lab.bus.get_node("flaky").state == "active"
    assert len([n for n in lab.bus.nodes if n.get_name() == "flaky"]) == 1


def test_workspace_overlay_keeps_builtin_executables_and_reports_unknown(tmp_path: Path) -> None:
    write_pkg(tmp_path, "rocketship", {"src/my_manager.py": "x = 1\n"})
    index = PackageIndex(workspace=tmp_path)
    exes = index.executables_of("rocketship")
    assert {"countdown", "main_controller", "my_manager.py", "my_manager"} <= set(exes)
    assert (
        index.share_dir("rocketship").name == "rocketship" and "server" in index.share_dir("rocketship").parts
    )
    with pytest.raises(ExecutableNotFoundError, match="no executable 'nope'"):
        index.factory("rocketship", "nope")


def test_student_node_calling_sys_exit_crashes_only_itself(tmp_path: Path) -> None:
    write_pkg(
        tmp_path,
        "my_pkg",
        {
            "quitter.py": """
            import sys
            from rclpy.node import Node

            class Quitter(Node):
                def __init__(self):
                    super().__init__('quitter')
                    self.create_timer(0.5, self.tick)

                def tick(self):
                    sys.exit('done here')
            """,
            "quits_early.py": """
            import sys
            from rclpy.node import Node

            class QuitsEarly(Node):
                def __init__(self):
                    super().__init__('quits_early')
                    sys.exit(3)
            """,
        },
    )
    lab = make_lab(tmp_path, start_delay="0")
    lab.run_node("my_pkg", "quitter.py")
    group = lab.run_node("my_pkg", "quits_early.py")
    assert "SystemExit" in (group.describe()["nodes"][0]["error"] or "")
    lab.executor.spin_until(3.0)
    quitter = lab.bus.get_node("quitter")
    assert quitter.state == "crashed" and "SystemExit: done here" in (quitter.crash_reason or "")
    assert lab.bus.topics["/countdown"].publish_count == 4, "the rocket's countdown ran on"
