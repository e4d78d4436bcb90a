"""Launch XML as a checked element tree that keeps line numbers.

expat builds the tree (``xml.etree`` drops line numbers) and refuses DOCTYPEs, entities,
processing instructions and stray text; a schema pass then checks every element and attribute,
including those a false ``if`` will skip, so a student's typo is reported whatever the
arguments are.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import NoReturn
from xml.parsers import expat

from server.services.launch.description import LaunchFileError

MAX_FILE_BYTES = 1024 * 1024
MAX_NESTING = 64  # element depth; keeps the recursive passes far from Python's recursion limit


@dataclass
class Element:
    tag: str
    attrs: dict[str, str]
    line: int
    children: list[Element] = field(default_factory=list)


def read_tree(data: bytes, file: str, encoding: str | None = None) -> Element:
    parser = expat.ParserCreate(encoding)
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[Element] = []
    roots: list[Element] = []

    def fail(problem: str) -> NoReturn:
        raise LaunchFileError(file, parser.CurrentLineNumber, problem)

    def start(tag: str, attrs: dict[str, str]) -> None:
        if len(stack) >= MAX_NESTING:
            fail(f"elements are nested more than {MAX_NESTING} deep")
        element = Element(tag, attrs, parser.CurrentLineNumber)
        (stack[-1].children if stack else roots).append(element)
        stack.append(element)

    def text(data: str) -> None:
        if data.strip():
            fail(f"unexpected text {data.strip()[:40]!r} inside <{stack[-1].tag}>")

    parser.StartElementHandler = start
    parser.EndElementHandler = lambda tag: stack.pop()
    parser.CharacterDataHandler = text
    parser.StartDoctypeDeclHandler = lambda *_: fail("DOCTYPE declarations are not allowed")
    parser.EntityDeclHandler = lambda *_: fail("entity declarations are not allowed")
    parser.ExternalEntityRefHandler = lambda *_: fail("external entities are not allowed")
    parser.ProcessingInstructionHandler = lambda target, _: fail(
        f"processing instruction <?{target} ...?> is not allowed"
    )
    try:
        parser.Parse(data, True)
    except expat.ExpatError as err:
        problem = f"malformed XML: {expat.ErrorString(err.code)} (column {err.offset + 1})"
        raise LaunchFileError(file, err.lineno, problem) from None
    return roots[0]


# --- Schema --------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Rule:
    attrs: frozenset[str]
    required: tuple[str, ...] = ()
    children: Mapping[str, str] = field(default_factory=dict)  # child tag -> rule name


ACTIONS: Mapping[str, str] = MappingProxyType(
    {
        "arg": "arg",
        "let": "let",
        "node": "node",
        "include": "include",
        "group": "group",
        "push-ros-namespace": "push-ros-namespace",
        "push_ros_namespace": "push-ros-namespace",
        "executable": "executable",
        "timer": "timer",
    }
)
_NODE_ATTRS = (
    "pkg",
    "exec",
    "type",
    "name",
    "namespace",
    "ns",
    "output",
    "respawn",
    "respawn_delay",
    "args",
    "ros_args",
)
_RULES: Mapping[str, _Rule] = MappingProxyType(
    {
        "launch": _Rule(frozenset({"version"}), children=ACTIONS),
        "group": _Rule(frozenset({"if", "unless"}), children=ACTIONS),
        "arg": _Rule(frozenset({"name", "default", "description", "value"}), ("name",)),
        "let": _Rule(frozenset({"name", "value"}), ("name", "value")),
        "push-ros-namespace": _Rule(frozenset({"namespace"}), ("namespace",)),
        "include": _Rule(frozenset({"file", "if", "unless"}), ("file",), {"arg": "include-arg"}),
        "include-arg": _Rule(frozenset({"name", "value"}), ("name", "value")),
        "node": _Rule(
            frozenset({*_NODE_ATTRS, "on_exit", "if", "unless"}),
            ("pkg",),
            {"param": "param", "remap": "remap"},
        ),
        "param": _Rule(frozenset({"name", "value", "from"}), (), {"param": "param"}),
        "remap": _Rule(frozenset({"from", "to"}), ("from", "to")),
        # A command (only ``ros2 ...`` runs: server/services/launch/commands.py), and actions some seconds later.
        "executable": _Rule(frozenset({"cmd", "name", "args", "shell", "output", "if", "unless"}), ("cmd",)),
        "timer": _Rule(frozenset({"period", "if", "unless"}), ("period",), children=ACTIONS),
    }
)


def did_you_mean(word: str, choices: Iterable[str], template: str = "'{}'") -> str:
    close = difflib.get_close_matches(word, sorted(choices), n=1)
    return f"; did you mean {template.format(close[0])}?" if close else ""


def _node_problem(element: Element) -> str | None:
    attrs = element.attrs
    if "exec" in attrs and "type" in attrs:
        return "<node> has both exec= and type= (the ROS 1 name); keep exec="
    if "exec" not in attrs and "type" not in attrs:
        return "<node> needs exec= (the executable to run; ROS 1 files call it type=)"
    if "namespace" in attrs and "ns" in attrs:
        return "<node> has both namespace= and ns= (the ROS 1 name); keep namespace="
    return None


def _arg_problem(element: Element) -> str | None:
    if "value" in element.attrs:
        name = element.attrs["name"]
        return (
            f'<arg name="{name}"> declares an argument and takes default=, not value= '
            "(use <let name=... value=...> for a constant)"
        )
    return None


def _param_problem(element: Element) -> str | None:
    if "from" in element.attrs:
        if "name" in element.attrs or "value" in element.attrs or element.children:
            return "<param from=...> loads a parameters file: it takes no name=, value= or nested <param>"
        return None
    if "name" not in element.attrs:
        return "<param> needs name= (or from= a parameters file)"
    name = element.attrs["name"]
    if "value" in element.attrs and element.children:
        return f'<param name="{name}"> has both value= and nested <param> elements'
    if "value" not in element.attrs and not element.children:
        return f'<param name="{name}"> needs value= (or nested <param> elements)'
    return None


_EXTRA_CHECKS: Mapping[str, Callable[[Element], str | None]] = MappingProxyType(
    {"node": _node_problem, "arg": _arg_problem, "param": _param_problem}
)


def check_tree(root: Element, file: str) -> None:
    """The tree against the launch schema (the same for XML and YAML files)."""
    if root.tag != "launch":
        raise LaunchFileError(file, root.line, f"the root element must be <launch>, not <{root.tag}>")
    _check_element(root, "launch", file)


def _check_element(element: Element, rule_name: str, file: str) -> None:
    rule = _RULES[rule_name]

    def fail(problem: str) -> NoReturn:
        raise LaunchFileError(file, element.line, problem)

    for attr in element.attrs:
        if attr not in rule.attrs:
            hint = did_you_mean(attr, rule.attrs)
            fail(
                f"unknown attribute '{attr}' on <{element.tag}>{hint}"
                f" (allowed: {', '.join(sorted(rule.attrs))})"
            )
    for attr in rule.required:
        if attr not in element.attrs:
            fail(f"<{element.tag}> needs the attribute '{attr}'")
    if "if" in element.attrs and "unless" in element.attrs:
        fail(f"<{element.tag}> has both if= and unless=; use one")
    extra = _EXTRA_CHECKS.get(rule_name)
    problem = extra(element) if extra else None
    if problem:
        fail(problem)
    for child in element.children:
        child_rule = rule.children.get(child.tag)
        if child_rule is None:
            raise LaunchFileError(file, child.line, _unknown_element(child.tag, element.tag, rule))
        _check_element(child, child_rule, file)


def _unknown_element(tag: str, parent: str, rule: _Rule) -> str:
    if not rule.children:
        return f"<{parent}> takes no child elements, found <{tag}>"
    allowed = ", ".join(f"<{name}>" for name in sorted(rule.children))
    hint = did_you_mean(tag, rule.children, "<{}>")
    return f"unknown element <{tag}> inside <{parent}>{hint} (allowed: {allowed})"


def declared_names(element: Element) -> set[str]:
    """Names of every ``<arg>`` declared in a file, whatever conditions will decide."""
    names: set[str] = set()
    for child in element.children:
        if child.tag == "arg":
            names.add(child.attrs["name"])
        elif child.tag in ("group", "timer"):
            names |= declared_names(child)
    return names


def load_tree(data: bytes, file: str, encoding: str | None = None) -> Element:
    if len(data) > MAX_FILE_BYTES:
        raise LaunchFileError(file, 0, f"file is larger than {MAX_FILE_BYTES} bytes; refusing to parse it")
    root = read_tree(data, file, encoding)
    check_tree(root, file)
    return root


def read_bytes(path: Path) -> bytes:
    with path.open("rb") as stream:
        return stream.read(MAX_FILE_BYTES + 1)  # one byte over is enough to refuse it
