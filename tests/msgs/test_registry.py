"""Looking message types up by their ROS name, in both spellings ros2 accepts."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from node_runtime.msgs import (
    Bool,
    Key,
    UnknownTypeError,
    definitions,
    get_type,
    normalize_type_name,
    type_names,
)


@pytest.mark.parametrize("name", ["std_msgs/Bool", "std_msgs/msg/Bool", " std_msgs/Bool "])
def test_get_type_either_spelling_finds_bool(name: str) -> None:
    assert get_type(name) is Bool


def test_get_type_keyboard_key_short_name_finds_key() -> None:
    assert get_type("keyboard_msgs/Key") is Key


@pytest.mark.parametrize("name", ["std_msgs/Foo", "Bool", "", "std_msgs/msg/bool", "foo_msgs/msg/Bool"])
def test_get_type_unknown_name_raises_naming_it(name: str) -> None:
    with pytest.raises(UnknownTypeError) as err:
        get_type(name)
    assert err.value.name == name
    assert isinstance(err.value, LookupError)
    assert repr(name) in str(err.value)


def test_normalize_type_name_short_form_gains_msg() -> None:
    assert normalize_type_name("geometry_msgs/Twist") == "geometry_msgs/msg/Twist"
    assert normalize_type_name("geometry_msgs/msg/Twist") == "geometry_msgs/msg/Twist"


def test_type_names_sorted_full_names() -> None:
    names = type_names()
    assert names == sorted(names)
    assert "std_msgs/msg/Bool" in names and "keyboard_msgs/msg/Key" in names
    assert all(n.count("/msg/") == 1 for n in names)


LAZY_PROBE = """
import json, sys
from std_msgs.msg import String
before = "node_runtime.msgs.generated.visualization_msgs" in sys.modules
from node_runtime.msgs import get_service_type, get_type
marker = get_type("visualization_msgs/msg/Marker")
lifecycle = get_service_type("lifecycle_msgs/srv/ChangeState")
print(json.dumps({"before": before, "marker": marker.__module__, "srv": lifecycle.TYPE,
                  "after": "node_runtime.msgs.generated.visualization_msgs" in sys.modules}))
"""


def test_a_package_s_classes_are_declared_when_one_of_its_types_is_first_asked_for() -> None:
    done = subprocess.run(
        [sys.executable, "-c", LAZY_PROBE], capture_output=True, text=True, timeout=60, check=True
    )
    seen = json.loads(done.stdout)
    assert seen == {
        "before": False,
        "marker": "node_runtime.msgs.generated.visualization_msgs",
        "srv": "lifecycle_msgs/srv/ChangeState",
        "after": True,
    }


def test_the_parsed_definitions_are_kept_and_parsed_again_when_a_file_changes(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    root = tmp_path / "interfaces"
    (root / "demo_msgs" / "msg").mkdir(parents=True)
    ping = root / "demo_msgs" / "msg" / "Ping.msg"
    ping.write_text("uint32 seq\n")
    monkeypatch.setattr(definitions, "_PARSED", tmp_path / ".parsed.pickle")
    first = definitions._cached(root)
    assert (tmp_path / ".parsed.pickle").is_file()
    kept = definitions._cached(root)
    assert kept == first and kept is not first  # read back, not parsed: equal, a new object
    ping.write_text("uint32 seq\nstring note\n")
    again = definitions._cached(root)
    assert [f.name for f in again.messages["demo_msgs/msg/Ping"].fields] == ["seq", "note"]


def test_without_ros_2_s_definitions_the_messages_say_what_to_run(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(definitions, "ROS_INTERFACES_DIR", tmp_path / "ros_interfaces")
    with pytest.raises(definitions.MissingDefinitionsError, match=r"run `python -m node_runtime.ros_wheels`"):
        definitions.lab_definitions.__wrapped__()
