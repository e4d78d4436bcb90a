"""ROS 2 naming rules: topic, node and namespace names; expansion, substitution and remapping."""

from __future__ import annotations

import pytest

from node_runtime.bus import (
    InvalidNameError,
    is_hidden,
    resolve_topic_name,
    validate_namespace,
    validate_node_name,
    validate_topic_name,
)


# -- topic names ------------------------------------------------------------------------------
@pytest.mark.parametrize(
    "name",
    [
        "chatter",
        "/chatter",
        "/a/b_c",
        "a/b",
        "_hidden",
        "/A9",
        "~",
        "~/private",
        "{node}",
        "a/{node}/b",
        "{ns}/x",
    ],
)
def test_validate_topic_name_valid_name_is_returned_unchanged(name: str) -> None:
    assert validate_topic_name(name) == name


@pytest.mark.parametrize(
    ("name", "problem"),
    [
        ("", "must not be empty"),
        ("/", "names no topic"),
        ("chatter/", "must not end with '/'"),
        ("/a/", "must not end with '/'"),
        ("a//b", "'//'"),
        ("//a", "'//'"),
        ("1abc", "must not start with a digit"),
        ("/a/1b", "must not start with a digit"),
        ("a-b", "only letters, digits and underscores"),
        ("a b", "only letters, digits and underscores"),
        ("a.b", "only letters, digits and underscores"),
        ("caf\u00e9", "only letters, digits and underscores"),
        ("~a", "'~' must be followed by '/'"),
        ("a/~", "'~' is allowed only as the first character"),
        ("a~", "'~' is allowed only as the first character"),
        ("/~/a", "'~' is allowed only as the first character"),
        ("~/", "names no topic"),
        ("a" * 248, "longer than 247"),
    ],
)
def test_validate_topic_name_invalid_name_raises_with_reason(name: str, problem: str) -> None:
    with pytest.raises(InvalidNameError) as err:
        validate_topic_name(name)
    assert err.value.kind == "topic"
    assert problem in str(err.value)
    assert isinstance(err.value, ValueError)


# -- node names and namespaces ----------------------------------------------------------------
@pytest.mark.parametrize("name", ["talker", "MainControllerNode", "_private", "node_2"])
def test_validate_node_name_valid_name_is_returned(name: str) -> None:
    assert validate_node_name(name) == name


@pytest.mark.parametrize("name", ["", "1node", "my-node", "a b", "ns/node", "~", "a" * 256])
def test_validate_node_name_invalid_name_raises(name: str) -> None:
    with pytest.raises(InvalidNameError) as err:
        validate_node_name(name)
    assert err.value.kind == "node"


@pytest.mark.parametrize(
    ("ns", "absolute"), [("", "/"), ("/", "/"), ("ns", "/ns"), ("/a/b", "/a/b"), ("/_x", "/_x")]
)
def test_validate_namespace_valid_namespace_is_made_absolute(ns: str, absolute: str) -> None:
    assert validate_namespace(ns) == absolute


@pytest.mark.parametrize("ns", ["/ns/", "/1ns", "/a//b", "/a-b", "/~", "/{node}"])
def test_validate_namespace_invalid_namespace_raises(ns: str) -> None:
    with pytest.raises(InvalidNameError) as err:
        validate_namespace(ns)
    assert err.value.kind == "namespace"


# -- resolution -------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("name", "namespace", "expected"),
    [
        ("chatter", "/", "/chatter"),
        ("chatter", "/ns", "/ns/chatter"),
        ("a/b", "/ns/inner", "/ns/inner/a/b"),
        ("/chatter", "/ns", "/chatter"),
        ("~", "/", "/talker"),
        ("~/x", "/", "/talker/x"),
        ("~/x", "/ns", "/ns/talker/x"),
        ("{node}/x", "/ns", "/ns/talker/x"),
        ("/{node}", "/ns", "/talker"),
        ("{ns}/x", "/robot", "/robot/x"),
        ("{namespace}/x", "/robot", "/robot/x"),
        ("{ns}/x", "/", "/x"),
        ("sub/{node}", "/robot", "/robot/sub/talker"),
    ],
)
def test_resolve_topic_name_expands_against_namespace_and_node(
    name: str, namespace: str, expected: str
) -> None:
    assert resolve_topic_name(name, "talker", namespace) == expected


def test_resolve_topic_name_unknown_substitution_raises() -> None:
    with pytest.raises(InvalidNameError, match="unknown substitution"):
        resolve_topic_name("{robot}/x", "talker", "/")


def test_resolve_topic_name_invalid_name_raises_before_expansion() -> None:
    with pytest.raises(InvalidNameError):
        resolve_topic_name("bad name", "talker", "/ns")


def test_resolve_topic_name_absolute_remap_rule_replaces_exact_match_only() -> None:
    rules = {"/ns/chatter": "/remapped"}
    assert resolve_topic_name("chatter", "talker", "/ns", rules) == "/remapped"
    assert resolve_topic_name("chatter2", "talker", "/ns", rules) == "/ns/chatter2"
    assert resolve_topic_name("/chatter", "talker", "/ns", rules) == "/chatter"


def test_resolve_topic_name_relative_remap_rule_expands_both_sides_in_namespace() -> None:
    # ROS 2 static remapping: `foo:=bar` in namespace /ns is `/ns/foo:=/ns/bar`.
    assert resolve_topic_name("countdown", "n", "/ns", {"countdown": "cd"}) == "/ns/cd"
    assert resolve_topic_name("/countdown", "n", "/", {"countdown": "cd"}) == "/cd"
    assert resolve_topic_name("/foo/bar", "n", "/ns", {"/foo/bar": "foo"}) == "/ns/foo"
    assert resolve_topic_name("x", "n", "/ns", {"x": "~/y"}) == "/ns/n/y"


def test_resolve_topic_name_invalid_remap_target_raises() -> None:
    with pytest.raises(InvalidNameError):
        resolve_topic_name("/countdown", "n", "/", {"/countdown": "bad name"})


@pytest.mark.parametrize(
    ("name", "hidden"), [("/_x", True), ("/a/_b/c", True), ("/a/b", False), ("/a_b", False)]
)
def test_is_hidden_token_with_leading_underscore_hides(name: str, hidden: bool) -> None:
    assert is_hidden(name) is hidden
