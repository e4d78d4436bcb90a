"""Reading .msg and .srv definitions: fields, defaults, arrays, bounds, constants, errors by line."""

from __future__ import annotations

import pytest
from rosbags.interfaces import Nodetype
from rosbags.typesys import get_types_from_msg

from node_runtime.msgs.definitions import lab_definitions, load_definitions
from node_runtime.msgs.idl import DefinitionError, parse_message, parse_service


def test_parse_message_primitives_nested_and_defaults() -> None:
    spec = parse_message(
        "demo_msgs/msg/Demo",
        "# a comment line\nfloat64 w 1  # trailing comment\nHeader header\nPoint p\nstd_msgs/Bool b\n"
        'string name "a # b"\nbool on true\n',
    )
    fields = {f.name: f for f in spec.fields}
    assert list(fields) == ["w", "header", "p", "b", "name", "on"]
    assert (fields["w"].base, fields["w"].default) == ("float64", 1.0)
    assert fields["header"].base == "std_msgs/msg/Header"
    assert fields["p"].base == "demo_msgs/msg/Point"  # unqualified: the same package
    assert fields["b"].base == "std_msgs/msg/Bool"
    assert fields["name"].default == "a # b"
    assert fields["on"].default is True
    assert spec.dependencies() == ("std_msgs/msg/Header", "demo_msgs/msg/Point", "std_msgs/msg/Bool")


def test_parse_message_arrays_bounds_and_their_type_text() -> None:
    spec = parse_message(
        "demo_msgs/msg/Arrays",
        "float64[9] cov\nint32[] any [1, 2]\nint32[<=3] few\nstring<=5 tag\nstring<=2[<=4] tags\n",
    )
    cov, any_, few, tag, tags = spec.fields
    assert (cov.array_size, cov.is_sequence, cov.type_text) == (9, False, "float64[9]")
    assert (any_.is_sequence, any_.array_bound, any_.default, any_.type_text) == (
        True,
        None,
        [1, 2],
        "int32[]",
    )
    assert (few.is_sequence, few.array_bound, few.type_text) == (True, 3, "int32[<=3]")
    assert (tag.string_bound, tag.is_array, tag.type_text) == (5, False, "string<=5")
    assert (tags.string_bound, tags.array_bound, tags.type_text) == (2, 4, "string<=2[<=4]")


def test_parse_message_constants_of_every_kind() -> None:
    spec = parse_message(
        "demo_msgs/msg/C", "uint8 A=3\nint16 B = -2\nfloat32 PI=3.5\nstring S=hello\nbool T=true\n"
    )
    assert [(c.name, c.base, c.value) for c in spec.constants] == [
        ("A", "uint8", 3),
        ("B", "int16", -2),
        ("PI", "float32", 3.5),
        ("S", "string", "hello"),
        ("T", "bool", True),
    ]
    assert spec.fields == ()


@pytest.mark.parametrize(
    ("text", "problem"),
    [
        ("float64", "expected 'TYPE NAME'"),
        ("uint8 A=300", "out of range for uint8"),
        ("int32 x 1.5", "not an integer"),
        ("Point p 3", "only primitive fields take a default"),
        ("int32 x\nint32 x", "defined twice"),
        ("uint8 lower=1", "UPPER_CASE"),
        ("int32<=3 x", "only strings take a bound"),
        ("float64 a__b", "bad field name"),
    ],
)
def test_parse_message_error_names_file_and_line(text: str, problem: str) -> None:
    with pytest.raises(DefinitionError) as err:
        parse_message("demo_msgs/msg/Bad", "# header\n" + text, source="demo_msgs/msg/Bad.msg")
    assert str(err.value).startswith("demo_msgs/msg/Bad.msg:")
    assert problem in str(err.value)


def test_parse_service_splits_request_and_response() -> None:
    spec = parse_service("demo_srvs/srv/Add", "# adds\nint64 a\nint64 b\n---\nint64 sum\n")
    assert spec.request.name == "demo_srvs/srv/Add_Request"
    assert [f.name for f in spec.request.fields] == ["a", "b"]
    assert [f.name for f in spec.response.fields] == ["sum"]
    with pytest.raises(DefinitionError, match="one '---' line"):
        parse_service("demo_srvs/srv/Bad", "int64 a\n")


def test_load_definitions_unknown_nested_type_is_an_error(tmp_path) -> None:  # type: ignore[no-untyped-def]
    folder = tmp_path / "demo_msgs" / "msg"
    folder.mkdir(parents=True)
    (folder / "Holder.msg").write_text("Missing thing\n")
    with pytest.raises(DefinitionError, match="unknown type demo_msgs/msg/Missing"):
        load_definitions(tmp_path)


def _rosbags_view(desc: tuple) -> tuple:  # type: ignore[type-arg]
    """(base, array size, sequence bound or None, string bound) from rosbags' field description."""
    kind, detail = desc
    if kind == Nodetype.BASE:
        return detail[0], None, None, detail[1] or None
    if kind == Nodetype.NAME:
        return detail, None, None, None
    inner, count = detail
    base, _, _, strbound = _rosbags_view(inner)
    if kind == Nodetype.ARRAY:
        return base, count, None, strbound
    return base, None, count or None, strbound


@pytest.mark.parametrize("name", sorted(lab_definitions().messages))
def test_every_lab_definition_parses_as_rosbags_parses_it(name: str) -> None:
    """rosbags' own parser, run on the same text, finds the same fields, bounds and constants."""
    spec = lab_definitions().messages[name]
    theirs = get_types_from_msg(spec.text, name)[name]
    consts, fields = theirs
    assert [(c[0], c[2]) for c in consts] == [(c.name, c.value) for c in spec.constants]
    mine = [(f.name, (f.base, f.array_size, f.array_bound, f.string_bound)) for f in spec.fields]
    assert [(n, _rosbags_view(d)) for n, d in fields] == mine
