"""Looking message types up by their ROS name, in both spellings ros2 accepts."""

from __future__ import annotations

import pytest

from server.msgs import Bool, Key, UnknownTypeError, get_type, normalize_type_name, type_names


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
