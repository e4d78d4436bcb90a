"""A workspace's interface packages become types with no build step: found as ROS declares them,
checked as their definitions say, hashed and laid out in CDR as rosbags (written apart) does; a
definition error is one line naming its file and line, and every other type still loads."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from support.app import REPO

from node_runtime.ament.interfaces import workspace_interfaces
from node_runtime.msgs import MessageError, UnknownTypeError, get_action_type, get_service_type, get_type
from node_runtime.msgs.schema import interface_text
from node_runtime.msgs.wire import deserialize, serialize, type_hash

from .interface_packages import (
    ACTION_CMAKE,
    ADD_THREE_INTS,
    NUM,
    SPHERE,
    TELEMETRY,
    TUTORIAL_CMAKE,
    interface_package,
    tutorial_workspace,
)
from .tutorial_packages import manifest, write


@pytest.fixture
def ws(tmp_path: Path) -> Path:
    tutorial_workspace(tmp_path)
    assert workspace_interfaces(tmp_path).problems == []
    return tmp_path


def rosbags_hash(definitions: dict[str, str], name: str) -> str:
    """RIHS01 as rosbags computes it from the definitions, over ROS 2 Kilted's own std/geometry msgs."""
    store = get_typestore(Stores.ROS2_KILTED)
    for type_name, text in definitions.items():
        store.register(get_types_from_msg(text, type_name))
    return str(store.hash_rihs01(name))


def test_tutorial_interfaces_nested_below_src_load_as_types(ws: Path) -> None:
    num, sphere = get_type("tutorial_interfaces/msg/Num"), get_type("tutorial_interfaces/Sphere")
    assert num(num=-3).num == -3
    assert type(sphere().center) is get_type("geometry_msgs/msg/Point")
    service = get_service_type("tutorial_interfaces/srv/AddThreeInts")
    assert service.Request(a=1, b=2, c=3).to_dict() == {"a": 1, "b": 2, "c": 3}
    assert service.Response().sum == 0
    assert sorted(workspace_interfaces(ws).packages) == [
        "custom_action_interfaces",
        "fleet_interfaces",
        "tutorial_interfaces",
    ]


def test_students_action_has_its_parts_wire_types_hash_and_definition(ws: Path) -> None:
    fibonacci = get_action_type("custom_action_interfaces/Fibonacci")
    assert fibonacci.Goal(order=5).order == 5 and list(fibonacci.Result(sequence=[0, 1]).sequence) == [0, 1]
    assert fibonacci.Impl.SendGoalService.TYPE == "custom_action_interfaces/action/Fibonacci_SendGoal"
    assert fibonacci.Impl.FeedbackMessage().feedback.partial_sequence.tolist() == []
    goal = "custom_action_interfaces/action/Fibonacci_Goal"
    assert type_hash(goal) == rosbags_hash({goal: "int32 order"}, goal)
    assert (
        interface_text(fibonacci.TYPE)
        == "int32 order\n---\nint32[] sequence\n---\nint32[] partial_sequence\n"
    )


def test_bad_action_names_its_file_and_the_line_in_its_section(tmp_path: Path) -> None:
    folder = tmp_path / "src/custom_action_interfaces"
    interface_package(
        folder,
        "custom_action_interfaces",
        ACTION_CMAKE,
        {"action/Fibonacci.action": "int32 order\n---\n# the answer\nNope sequence\n---\n"},
    )
    problems = workspace_interfaces(tmp_path).problems
    assert problems == [
        f"{folder / 'action/Fibonacci.action'}:4: unknown type custom_action_interfaces/msg/Nope"
    ]


def test_telemetry_has_its_constants_defaults_and_bounds(ws: Path) -> None:
    telemetry = get_type("fleet_interfaces/msg/Telemetry")
    assert (telemetry.MODE_IDLE, telemetry.MODE_FLYING, telemetry.MAX_CODES) == (0, 1, 4)
    assert telemetry.CALLSIGN_PREFIX == "uav_"
    msg = telemetry()
    assert (msg.callsign, msg.mode, list(msg.samples)) == ("uav_1", 1, [1.5, 2.5])
    assert msg.position.tolist() == [0.0, 0.0, 0.0] and len(msg.corners) == 2 and msg.codes.tolist() == []
    msg.codes = [1, 2, 3, 4]
    msg.tags = ["a" * 8]
    for field, value, problem in [
        ("callsign", "x" * 13, "longer than 12"),
        ("codes", [1, 2, 3, 4, 5], "more than 4"),
        ("position", [1.0, 2.0], "exactly 3"),
        ("tags", ["a" * 9], "longer than 8"),
        ("mode", 256, "out of range"),
        ("counts", [get_type("std_msgs/msg/Int64")()], "expected tutorial_interfaces"),
    ]:
        with pytest.raises(MessageError, match=problem):
            setattr(msg, field, value)


def test_rihs01_hashes_equal_rosbags_from_the_definitions(ws: Path) -> None:
    tutorial = {"tutorial_interfaces/msg/Num": NUM, "tutorial_interfaces/msg/Sphere": SPHERE}
    for name in tutorial:
        assert type_hash(name) == rosbags_hash(tutorial, name)
    fleet = {**tutorial, "fleet_interfaces/msg/Telemetry": TELEMETRY}
    assert type_hash("fleet_interfaces/msg/Telemetry") == rosbags_hash(
        fleet, "fleet_interfaces/msg/Telemetry"
    )
    # The constants are not part of the hash (REP-2016), but every field is.
    assert type_hash("tutorial_interfaces/msg/Num") != type_hash("std_msgs/msg/Int64")


def test_cdr_of_telemetry_decodes_with_rosbags_and_round_trips(ws: Path) -> None:
    telemetry, num = get_type("fleet_interfaces/msg/Telemetry"), get_type("tutorial_interfaces/msg/Num")
    msg = telemetry(
        callsign="uav_7",
        position=[1.0, 2.0, 3.0],
        codes=[7, 8],
        tags=["red", "lead"],
        counts=[num(num=5), num(num=-5)],
    )
    msg.header.frame_id = "map"
    data = serialize(msg)
    store = get_typestore(Stores.ROS2_KILTED)
    for name, text in [("tutorial_interfaces/msg/Num", NUM), ("fleet_interfaces/msg/Telemetry", TELEMETRY)]:
        store.register(get_types_from_msg(text, name))
    raw = store.deserialize_cdr(data, "fleet_interfaces/msg/Telemetry")
    assert (raw.header.frame_id, raw.callsign, raw.mode) == ("map", "uav_7", 1)
    assert raw.position.tolist() == [1.0, 2.0, 3.0] and raw.codes.tolist() == [7, 8]
    assert raw.tags == ["red", "lead"] and [c.num for c in raw.counts] == [5, -5]
    assert np.allclose(raw.samples, [1.5, 2.5]) and len(raw.corners) == 2
    assert deserialize("fleet_interfaces/msg/Telemetry", data) == msg


BAD_DEFINITIONS = [
    ("unknown type", "int32 good\nNoSuchType thing\n", 2, "unknown type bad_interfaces/msg/NoSuchType"),
    ("unknown package", "float64 x\n\nnope_msgs/Thing thing\n", 3, "unknown type nope_msgs/msg/Thing"),
    ("bad syntax", "# fine\nint32\n", 2, "expected 'TYPE NAME'"),
    ("bad constant", "uint8 LOW=0\nuint8 HIGH=300\n", 2, "300 is out of range for uint8"),
    ("constant not a number", "int32 LIMIT=ten\n", 1, "is not an integer"),
    ("bad default", "bool flag maybe\n", 1, "'maybe' is not a bool"),
    ("bound on a number", "int32<=5 x\n", 1, "only strings take a bound"),
    ("field twice", "int32 x\nfloat64 x\n", 2, "'x' defined twice"),
]


@pytest.mark.parametrize(
    ("kind", "text", "line", "problem"), BAD_DEFINITIONS, ids=[b[0] for b in BAD_DEFINITIONS]
)
def test_definition_error_is_one_line_naming_file_and_line_and_the_rest_loads(
    tmp_path: Path, kind: str, text: str, line: int, problem: str
) -> None:
    folder = tmp_path / "src/bad_interfaces"
    cmake = TUTORIAL_CMAKE.replace("tutorial_interfaces", "bad_interfaces").replace(
        '"msg/Num.msg"\n  "msg/Sphere.msg"\n  "srv/AddThreeInts.srv"',
        '"msg/Good.msg" "msg/Bad.msg" "msg/Uses.msg"',
    )
    interface_package(
        folder,
        "bad_interfaces",
        cmake,
        {
            "msg/Good.msg": "int32 value\n",
            "msg/Bad.msg": text,
            "msg/Uses.msg": "Good good\nBad bad\n",
        },
    )
    problems = workspace_interfaces(tmp_path).problems
    bad, uses = folder / "msg/Bad.msg", folder / "msg/Uses.msg"
    if kind.startswith("unknown"):  # Bad.msg parses; what it nests is missing
        assert problems[0] == f"{bad}:{line}: {problem}"
    else:
        assert len(problems) == 2 and problems[0].startswith(f"{bad}:{line}: ") and problem in problems[0]
    assert problems[-1] == f"{uses}:2: bad_interfaces/msg/Bad did not load (see its own error)"
    assert all("\n" not in p for p in problems)
    assert get_type("bad_interfaces/msg/Good")(value=3).value == 3
    for name in ("bad_interfaces/msg/Bad", "bad_interfaces/msg/Uses"):
        with pytest.raises(UnknownTypeError):
            get_type(name)


def test_file_the_cmakelists_names_but_is_missing_names_the_cmakelists_line(tmp_path: Path) -> None:
    folder = tmp_path / "src/tutorial_interfaces"
    interface_package(
        folder,
        "tutorial_interfaces",
        TUTORIAL_CMAKE,
        {"msg/Num.msg": NUM, "srv/AddThreeInts.srv": ADD_THREE_INTS},
    )
    problems = workspace_interfaces(tmp_path).problems
    assert problems == [f"{folder / 'CMakeLists.txt'}:10: no file msg/Sphere.msg in {folder}"]
    assert get_type("tutorial_interfaces/msg/Num")().num == 0


def test_bad_service_names_its_line_after_the_separator(tmp_path: Path) -> None:
    folder = tmp_path / "src/calc_interfaces"
    write(
        folder,
        {
            "package.xml": manifest("calc_interfaces", "ament_cmake").replace(
                "<export>", "<member_of_group>rosidl_interface_packages</member_of_group>\n  <export>"
            ),
            "srv/Add.srv": "int64 a\n---\nint64 sum\nint64 sum\n",
            "srv/Twice.srv": "int64 a\n---\n---\n",
        },
    )
    problems = workspace_interfaces(tmp_path).problems
    assert f"{folder / 'srv/Add.srv'}:4: 'sum' defined twice" in problems
    assert f"{folder / 'srv/Twice.srv'}:3: a service has one '---' line, found 2" in problems


def test_member_of_the_group_without_rosidl_call_has_every_file_a_plain_package_none(tmp_path: Path) -> None:
    write(
        tmp_path / "src",
        {
            "grouped/package.xml": manifest("grouped", "ament_cmake").replace(
                "<export>", "<member_of_group>rosidl_interface_packages</member_of_group>\n  <export>"
            ),
            "grouped/msg/Ping.msg": "uint32 seq\n",
            "grouped/srv/Echo.srv": "string text\n---\nstring text\n",
            "plain/package.xml": manifest("plain", "ament_cmake"),
            "plain/msg/Unused.msg": "int32 x\n",
        },
    )
    reader = workspace_interfaces(tmp_path)
    assert list(reader.packages) == ["grouped"] and reader.problems == []
    assert get_type("grouped/msg/Ping")(seq=4).seq == 4
    assert get_service_type("grouped/Echo").Request(text="hi").text == "hi"
    with pytest.raises(UnknownTypeError):
        get_type("plain/msg/Unused")


def test_changed_definition_and_new_package_are_read_on_next_lookup(ws: Path) -> None:
    before = type_hash("tutorial_interfaces/msg/Num")
    (ws / "src/tutorials/tutorial_interfaces/msg/Num.msg").write_text("int64 num\nstring label\n")
    interface_package(
        ws / "src/later_interfaces",
        "later_interfaces",
        TUTORIAL_CMAKE.replace("tutorial_interfaces", "later_interfaces").replace(
            '"msg/Num.msg"\n  "msg/Sphere.msg"\n  "srv/AddThreeInts.srv"', '"msg/Late.msg"'
        ),
        {"msg/Late.msg": "tutorial_interfaces/Num num\n"},
    )
    late = get_type("later_interfaces/msg/Late")  # not known yet: the lookup reads the workspace again
    assert late().num.label == ""
    assert get_type("tutorial_interfaces/msg/Num")(label="x").label == "x"
    assert type_hash("tutorial_interfaces/msg/Num") != before


def test_copy_of_a_labs_own_type_is_the_labs_and_a_different_one_is_refused(tmp_path: Path) -> None:
    key = (REPO / "node_runtime/msgs/interfaces/keyboard_msgs/msg/Key.msg").read_text()
    group = "<member_of_group>rosidl_interface_packages</member_of_group>\n  <export>"
    write(
        tmp_path / "src",
        {
            "keyboard_msgs/package.xml": manifest("keyboard_msgs", "ament_cmake").replace("<export>", group),
            "keyboard_msgs/msg/Key.msg": "# the course's copy\n" + key,
            "std_msgs/package.xml": manifest("std_msgs", "ament_cmake").replace("<export>", group),
            "std_msgs/msg/Bool.msg": "int32 data\n",
        },
    )
    problems = workspace_interfaces(tmp_path).problems
    bool_file = tmp_path / "src/std_msgs/msg/Bool.msg"
    assert problems == [f"{bool_file}: std_msgs/msg/Bool differs from the lab's own; the lab's is used"]
    assert get_type("std_msgs/msg/Bool")(data=True).data is True


IMPORTS = """
from tutorial_interfaces.msg import Num, Sphere
from tutorial_interfaces.srv import AddThreeInts
from fleet_interfaces.msg import Telemetry
from custom_action_interfaces.action import Fibonacci
import tutorial_interfaces.msg as module

print(Num(num=4), Sphere().radius, AddThreeInts.Request(c=2).c, Telemetry.MODE_FLYING, module.__all__)
print(Fibonacci.Goal(order=3))
if __name__ == '__main__':
    pass
"""

IMPORTS_BAD = """
from tutorial_interfaces.msg import Num
print('Num imports', Num(num=1).num, flush=True)
from tutorial_interfaces.msg import Broken

if __name__ == '__main__':
    pass
"""


def run_node_file(ws: Path, source: str) -> subprocess.CompletedProcess[str]:
    node = ws / "node.py"
    node.write_text(textwrap.dedent(source))
    env = {**os.environ, "ROS2LAB_WORKSPACE": str(ws)}
    return subprocess.run(
        [sys.executable, "-m", "node_runtime.process.runner", str(node)],
        env=env,
        cwd=REPO,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
    )


def test_node_process_imports_the_workspaces_types(ws: Path) -> None:
    done = run_node_file(ws, IMPORTS)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        "tutorial_interfaces.msg.Num(num=4) 0.0 2 1 ['Num', 'Sphere']",
        "custom_action_interfaces.action.Fibonacci_Goal(order=3)",
    ]


def test_node_importing_a_broken_type_exits_1_with_one_line_naming_the_definition(ws: Path) -> None:
    folder = ws / "src/tutorials/tutorial_interfaces"
    (folder / "msg/Broken.msg").write_text("int64 num\nfloat64 x y z\n")
    (folder / "CMakeLists.txt").write_text(
        TUTORIAL_CMAKE.replace('"msg/Num.msg"', '"msg/Num.msg" "msg/Broken.msg"')
    )
    done = run_node_file(ws, IMPORTS_BAD)
    assert done.returncode == 1
    assert done.stdout == "Num imports 1\n"
    assert done.stderr.splitlines() == [
        f"{ws / 'node.py'}:4: ImportError: {folder / 'msg/Broken.msg'}:2: 'y z' is not a number"
    ], done.stderr
