"""Parse the subset of ROS 2 launch XML the lab uses into a ``LaunchDescription``.

Three stages, one section each below:

1. expat builds a small element tree that keeps line numbers (``xml.etree`` drops them) and
   refuses DOCTYPEs, entities, processing instructions and stray text;
2. a schema pass checks every element and attribute, including those a false ``if`` will skip,
   so a student's typo is reported whatever the arguments are;
3. an evaluation pass performs substitutions and conditions, follows includes (each included
   file has its own argument scope) and collects the nodes in document order.

Nothing is executed: the result is plain data for the launcher.
"""

from __future__ import annotations

import difflib
import os
import re
from collections import ChainMap
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import NoReturn, cast
from xml.parsers import expat

from .description import (
    LaunchDescription,
    LaunchFileError,
    NodeAction,
    ParamScalar,
    ParamValue,
    SourceLocation,
)

MAX_FILE_BYTES = 1024 * 1024
MAX_NESTING = 64  # element depth; keeps the recursive passes far from Python's recursion limit
MAX_INCLUDE_DEPTH = 32
MAX_FILES_READ = 256  # counted with repetition: a diamond of includes doubles the work per level

FindPackageShare = Callable[[str], Path]
"""Maps a package name to its share directory; raises ``LookupError`` for an unknown package."""

_NO_ARGS: Mapping[str, str] = MappingProxyType({})


# --- 1. Element tree with line numbers ------------------------------------------------------


@dataclass
class _Element:
    tag: str
    attrs: dict[str, str]
    line: int
    children: list[_Element] = field(default_factory=list)


def _read_tree(data: bytes, file: str, encoding: str | None = None) -> _Element:
    parser = expat.ParserCreate(encoding)
    parser.SetParamEntityParsing(expat.XML_PARAM_ENTITY_PARSING_NEVER)
    stack: list[_Element] = []
    roots: list[_Element] = []

    def fail(problem: str) -> NoReturn:
        raise LaunchFileError(file, parser.CurrentLineNumber, problem)

    def start(tag: str, attrs: dict[str, str]) -> None:
        if len(stack) >= MAX_NESTING:
            fail(f"elements are nested more than {MAX_NESTING} deep")
        element = _Element(tag, attrs, parser.CurrentLineNumber)
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


# --- 2. Schema ------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Rule:
    attrs: frozenset[str]
    required: tuple[str, ...] = ()
    children: Mapping[str, str] = field(default_factory=dict)  # child tag -> rule name


_ACTIONS: Mapping[str, str] = MappingProxyType(
    {
        "arg": "arg",
        "let": "let",
        "node": "node",
        "include": "include",
        "group": "group",
        "push-ros-namespace": "push-ros-namespace",
        "push_ros_namespace": "push-ros-namespace",
    }
)
_NODE_ATTRS = ("pkg", "exec", "type", "name", "namespace", "ns", "output", "respawn", "respawn_delay")
_RULES: Mapping[str, _Rule] = MappingProxyType(
    {
        "launch": _Rule(frozenset({"version"}), children=_ACTIONS),
        "group": _Rule(frozenset({"if", "unless"}), children=_ACTIONS),
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
        "param": _Rule(frozenset({"name", "value", "from"}), ("name",), {"param": "param"}),
        "remap": _Rule(frozenset({"from", "to"}), ("from", "to")),
    }
)


def _did_you_mean(word: str, choices: Iterable[str], template: str = "'{}'") -> str:
    close = difflib.get_close_matches(word, sorted(choices), n=1)
    return f"; did you mean {template.format(close[0])}?" if close else ""


def _node_problem(element: _Element) -> str | None:
    attrs = element.attrs
    if "exec" in attrs and "type" in attrs:
        return "<node> has both exec= and type= (the ROS 1 name); keep exec="
    if "exec" not in attrs and "type" not in attrs:
        return "<node> needs exec= (the executable to run; ROS 1 files call it type=)"
    if "namespace" in attrs and "ns" in attrs:
        return "<node> has both namespace= and ns= (the ROS 1 name); keep namespace="
    return None


def _arg_problem(element: _Element) -> str | None:
    if "value" in element.attrs:
        name = element.attrs["name"]
        return (
            f'<arg name="{name}"> declares an argument and takes default=, not value= '
            "(use <let name=... value=...> for a constant)"
        )
    return None


def _param_problem(element: _Element) -> str | None:
    name = element.attrs["name"]
    if "from" in element.attrs:
        return f'<param name="{name}" from=...>: parameter files are not supported; give value= instead'
    if "value" in element.attrs and element.children:
        return f'<param name="{name}"> has both value= and nested <param> elements'
    if "value" not in element.attrs and not element.children:
        return f'<param name="{name}"> needs value= (or nested <param> elements)'
    return None


_EXTRA_CHECKS: Mapping[str, Callable[[_Element], str | None]] = MappingProxyType(
    {"node": _node_problem, "arg": _arg_problem, "param": _param_problem}
)


def _check_tree(root: _Element, file: str) -> None:
    if root.tag != "launch":
        raise LaunchFileError(file, root.line, f"the root element must be <launch>, not <{root.tag}>")
    _check_element(root, "launch", file)


def _check_element(element: _Element, rule_name: str, file: str) -> None:
    rule = _RULES[rule_name]

    def fail(problem: str) -> NoReturn:
        raise LaunchFileError(file, element.line, problem)

    for attr in element.attrs:
        if attr not in rule.attrs:
            hint = _did_you_mean(attr, rule.attrs)
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
    hint = _did_you_mean(tag, rule.children, "<{}>")
    return f"unknown element <{tag}> inside <{parent}>{hint} (allowed: {allowed})"


def _declared_names(element: _Element) -> set[str]:
    """Names of every ``<arg>`` declared in a file, whatever conditions will decide."""
    names: set[str] = set()
    for child in element.children:
        if child.tag == "arg":
            names.add(child.attrs["name"])
        elif child.tag == "group":
            names |= _declared_names(child)
    return names


def _load_tree(data: bytes, file: str, encoding: str | None = None) -> _Element:
    if len(data) > MAX_FILE_BYTES:
        raise LaunchFileError(file, 0, f"file is larger than {MAX_FILE_BYTES} bytes; refusing to parse it")
    root = _read_tree(data, file, encoding)
    _check_tree(root, file)
    return root


# --- 3. Substitutions -----------------------------------------------------------------------


class _SubstitutionError(ValueError):
    """A substitution cannot be parsed or resolved; the caller adds file and line."""


_SUBSTITUTION_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]*")
_SUPPORTED = ("var", "find-pkg-share", "env", "dirname")
_UNSUPPORTED_HINTS: Mapping[str, str] = MappingProxyType(
    {
        "eval": "$(eval ...) is not supported here; compute the value with an <arg> instead",
        "arg": "$(arg NAME) is ROS 1 syntax; ROS 2 writes $(var NAME)",
        "find": "$(find PKG) is ROS 1 syntax; ROS 2 writes $(find-pkg-share PKG)",
        "optenv": "$(optenv NAME DEFAULT) is ROS 1 syntax; ROS 2 writes $(env NAME DEFAULT)",
    }
)
_Resolve = Callable[[str, list[str]], str]


def _substitute(text: str, resolve: _Resolve) -> str:
    """Expand every ``$(name arg ...)`` in ``text``; arguments may nest substitutions or be quoted."""
    return _expand(text, 0, resolve, in_argument=False)[0]


def _expand(text: str, pos: int, resolve: _Resolve, *, in_argument: bool) -> tuple[str, int]:
    parts: list[str] = []
    while pos < len(text):
        if text.startswith("$(", pos):
            value, pos = _expand_one(text, pos + 2, resolve)
            parts.append(value)
        elif in_argument and (text[pos].isspace() or text[pos] == ")"):
            break
        else:
            parts.append(text[pos])
            pos += 1
    return "".join(parts), pos


def _expand_one(text: str, pos: int, resolve: _Resolve) -> tuple[str, int]:
    start = pos - 2
    match = _SUBSTITUTION_NAME.match(text, pos)
    if match is None:
        raise _SubstitutionError(f"expected a substitution name after '$(' in {text[start:]!r}")
    name, pos = match.group(), match.end()
    if name not in _SUPPORTED:
        supported = ", ".join(f"$({known})" for known in _SUPPORTED)
        raise _SubstitutionError(
            _UNSUPPORTED_HINTS.get(name, f"unknown substitution $({name}); use {supported}")
        )
    args: list[str] = []
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos >= len(text):
            raise _SubstitutionError(f"unterminated substitution {text[start:]!r}: missing ')'")
        if text[pos] == ")":
            return resolve(name, args), pos + 1
        if text[pos] in "'\"":
            close = text.find(text[pos], pos + 1)
            if close < 0:
                raise _SubstitutionError(f"unterminated quote in {text[start:]!r}")
            args.append(text[pos + 1 : close])
            pos = close + 1
        else:
            arg, pos = _expand(text, pos, resolve, in_argument=True)
            args.append(arg)


def _package_not_found(pkg: str, err: LookupError) -> str:
    detail = "" if isinstance(err, KeyError) else str(err)  # KeyError's str() is just the quoted key
    return detail if f"'{pkg}'" in detail else f"package '{pkg}' not found"


def _arity(name: str, args: list[str], low: int, high: int) -> None:
    if not low <= len(args) <= high:
        expected = f"{low}" if low == high else f"{low} to {high}"
        raise _SubstitutionError(f"$({name}) takes {expected} argument(s), got {len(args)}")


# --- 4. Typed values ------------------------------------------------------------------------

_INT = re.compile(r"[-+]?[0-9]+\Z")
_FLOAT = re.compile(r"[-+]?([0-9]+\.[0-9]*|\.[0-9]+|[0-9]+(?=[eE]))([eE][-+]?[0-9]+)?\Z")
_OUTPUTS = ("screen", "log", "both", "own_log", "full")


def _parse_bool(text: str) -> bool | None:
    lowered = text.strip().lower()
    if lowered in ("true", "1"):
        return True
    if lowered in ("false", "0"):
        return False
    return None


def _typed_scalar(text: str) -> ParamScalar:
    text = text.strip()
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "'\"":
        return text[1:-1]
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    if _INT.match(text):
        return int(text)
    if _FLOAT.match(text):
        return float(text)
    return text


def _typed_param(text: str) -> ParamValue:
    """Type a parameter value as ROS launch does: bool, int, float, a uniform ``[...]`` list, or str."""
    stripped = text.strip()
    if not (stripped.startswith("[") and stripped.endswith("]")):
        return _typed_scalar(text)
    raw_items = _split_list(stripped[1:-1])
    if any(item.strip().startswith("[") for item in raw_items):
        raise ValueError(f"{stripped} nests lists, which a ROS parameter cannot hold")
    items = [_typed_scalar(item) for item in raw_items]
    kinds = sorted({type(item).__name__ for item in items})
    if len(kinds) > 1:
        hint = " (write 1.0, not 1, in a list of floats)" if kinds == ["float", "int"] else ""
        raise ValueError(f"{stripped} mixes {' and '.join(kinds)}; a ROS parameter list holds one type{hint}")
    return cast(ParamValue, items)


def _split_list(body: str) -> list[str]:
    if not body.strip():
        return []
    items: list[str] = []
    current: list[str] = []
    quote: str | None = None
    for char in body:
        if quote is None and char == ",":
            items.append("".join(current))
            current = []
            continue
        if quote is None and char in "'\"":
            quote = char
        elif char == quote:
            quote = None
        current.append(char)
    items.append("".join(current))
    return items


def _join_namespace(outer: str | None, inner: str) -> str | None:
    if not inner:
        return outer
    if inner.startswith("/"):
        return inner
    return (outer or "").rstrip("/") + "/" + inner


# --- 5. Evaluation --------------------------------------------------------------------------


@dataclass
class _Session:
    find_package_share: FindPackageShare
    environ: Mapping[str, str]
    nodes: list[NodeAction] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    files_read: int = 1

    def note_file(self, file: str) -> None:
        if file not in self.files:
            self.files.append(file)


@dataclass
class _Frame:
    """What a group sees: its variables (scoped by ChainMap) and its pushed namespace."""

    variables: ChainMap[str, str]
    namespace: str | None


class _FileEvaluator:
    """Evaluates one file's actions; ``origin`` names who passed ``passed`` (for error messages)."""

    def __init__(
        self,
        session: _Session,
        file: str,
        passed: Mapping[str, str],
        stack: tuple[Path, ...],
        origin: str,
    ) -> None:
        self.session = session
        self.file = file
        self.passed = passed
        self.stack = stack
        self.origin = origin
        self.declared: dict[str, str] = {}
        self.declared_at: dict[str, int] = {}

    def run(self, root: _Element, namespace: str | None) -> dict[str, str]:
        self._run_actions(root, _Frame(ChainMap({}), namespace))
        return self.declared

    def _error(self, element: _Element, problem: str) -> LaunchFileError:
        return LaunchFileError(self.file, element.line, problem)

    def _run_actions(self, parent: _Element, frame: _Frame) -> None:
        handlers: Mapping[str, Callable[[_Element, _Frame], None]] = {
            "arg": self._run_arg,
            "let": self._run_let,
            "node": self._run_node,
            "include": self._run_include,
            "group": self._run_group,
            "push-ros-namespace": self._run_push_namespace,
        }
        for element in parent.children:
            if self._active(element, frame):
                handlers[_ACTIONS[element.tag]](element, frame)

    # -- attributes

    def _sub(self, element: _Element, attr: str, frame: _Frame) -> str:
        raw = element.attrs[attr]

        def resolve(name: str, args: list[str]) -> str:
            return self._resolve(name, args, frame)

        try:
            return _substitute(raw, resolve)
        except _SubstitutionError as err:
            raise self._error(element, f'in {attr}="{raw}": {err}') from None

    def _optional(self, element: _Element, attr: str, frame: _Frame) -> str | None:
        return self._sub(element, attr, frame) if attr in element.attrs else None

    def _resolve(self, name: str, args: list[str], frame: _Frame) -> str:
        if name == "var":
            _arity(name, args, 1, 1)
            if args[0] not in frame.variables:
                hint = _did_you_mean(args[0], frame.variables) or " (declare it with <arg> above this line)"
                raise _SubstitutionError(f"no argument or variable '{args[0]}' is defined here{hint}")
            return frame.variables[args[0]]
        if name == "find-pkg-share":
            _arity(name, args, 1, 1)
            try:
                return str(self.session.find_package_share(args[0]))
            except LookupError as err:
                raise _SubstitutionError(_package_not_found(args[0], err)) from None
        if name == "env":
            _arity(name, args, 1, 2)
            value = self.session.environ.get(args[0])
            if value is None and len(args) == 1:
                raise _SubstitutionError(f"environment variable '{args[0]}' is not set (no default given)")
            return value if value is not None else args[1]
        _arity(name, args, 0, 0)  # dirname
        return str(Path(self.file).parent)

    def _active(self, element: _Element, frame: _Frame) -> bool:
        for attr, wanted in (("if", True), ("unless", False)):
            if attr in element.attrs:
                value = self._sub(element, attr, frame)
                truth = _parse_bool(value)
                if truth is None:
                    raise self._error(
                        element, f'{attr}="{value}" is not a condition: use true, false, 1 or 0'
                    )
                return truth == wanted
        return True

    # -- actions

    def _run_arg(self, element: _Element, frame: _Frame) -> None:
        name = element.attrs["name"]
        if name in self.declared_at:
            raise self._error(
                element, f"argument '{name}' is declared twice (first at line {self.declared_at[name]})"
            )
        if name in self.passed:
            value = self.passed[name]
        elif "default" in element.attrs:
            value = self._sub(element, "default", frame)
        else:
            raise self._error(
                element,
                f"argument '{name}' is required: it has no default and {self.origin} does not give it",
            )
        self.declared_at[name] = element.line
        self.declared[name] = value
        frame.variables[name] = value

    def _run_let(self, element: _Element, frame: _Frame) -> None:
        frame.variables[element.attrs["name"]] = self._sub(element, "value", frame)

    def _run_group(self, element: _Element, frame: _Frame) -> None:
        self._run_actions(element, _Frame(frame.variables.new_child(), frame.namespace))

    def _run_push_namespace(self, element: _Element, frame: _Frame) -> None:
        frame.namespace = _join_namespace(frame.namespace, self._sub(element, "namespace", frame))

    def _run_node(self, element: _Element, frame: _Frame) -> None:
        pkg = self._sub(element, "pkg", frame)
        executable = self._sub(element, "exec" if "exec" in element.attrs else "type", frame)
        if not pkg or not executable:
            raise self._error(element, "<node> has an empty pkg= or exec=")
        node_ns = self._optional(element, "namespace" if "namespace" in element.attrs else "ns", frame)
        output = self._optional(element, "output", frame)
        if output is not None and output not in _OUTPUTS:
            raise self._error(element, f'output="{output}" is not one of {", ".join(_OUTPUTS)}')
        on_exit = self._optional(element, "on_exit", frame)
        if on_exit not in (None, "shutdown"):
            raise self._error(element, f'on_exit="{on_exit}" is not supported; the only value is "shutdown"')
        parameters: list[tuple[str, ParamValue]] = []
        self._collect_params(element, frame, "", parameters, {})
        remappings = tuple(
            (self._sub(child, "from", frame), self._sub(child, "to", frame))
            for child in element.children
            if child.tag == "remap"
        )
        self.session.nodes.append(
            NodeAction(
                pkg=pkg,
                exec=executable,
                name=self._optional(element, "name", frame),
                namespace=frame.namespace if node_ns is None else _join_namespace(frame.namespace, node_ns),
                output=output,
                respawn=self._respawn(element, frame),
                respawn_delay_s=self._respawn_delay_s(element, frame),
                parameters=tuple(parameters),
                remappings=remappings,
                location=SourceLocation(self.file, element.line),
                shutdown_on_exit=on_exit == "shutdown",
            )
        )

    def _respawn(self, element: _Element, frame: _Frame) -> bool:
        text = self._optional(element, "respawn", frame)
        value = False if text is None else _parse_bool(text)
        if value is None:
            raise self._error(element, f'respawn="{text}" is not a boolean: use true or false')
        return value

    def _respawn_delay_s(self, element: _Element, frame: _Frame) -> float:
        text = self._optional(element, "respawn_delay", frame)
        if text is None:
            return 0.0
        try:
            delay_s = float(text)
        except ValueError:
            delay_s = -1.0
        if not 0.0 <= delay_s < float("inf"):
            raise self._error(element, f'respawn_delay="{text}" is not a number of seconds >= 0')
        return delay_s

    def _collect_params(
        self,
        parent: _Element,
        frame: _Frame,
        prefix: str,
        out: list[tuple[str, ParamValue]],
        seen: dict[str, int],
    ) -> None:
        for child in parent.children:
            if child.tag != "param":
                continue
            name = prefix + self._sub(child, "name", frame)
            if child.children:
                self._collect_params(child, frame, name + ".", out, seen)
                continue
            if name in seen:
                raise self._error(child, f"parameter '{name}' is set twice (first at line {seen[name]})")
            seen[name] = child.line
            try:
                out.append((name, _typed_param(self._sub(child, "value", frame))))
            except ValueError as err:
                raise self._error(child, f"parameter '{name}': {err}") from None

    def _run_include(self, element: _Element, frame: _Frame) -> None:
        path = Path(self._sub(element, "file", frame))
        if not path.is_absolute():
            path = Path(self.file).parent / path
        passed: dict[str, str] = {}
        for arg in element.children:
            if arg.attrs["name"] in passed:
                raise self._error(arg, f"argument '{arg.attrs['name']}' is passed twice")
            passed[arg.attrs["name"]] = self._sub(arg, "value", frame)
        root = self._load_include(element, path)
        declared = _declared_names(root)
        for arg in element.children:
            if arg.attrs["name"] not in declared:
                hint = _did_you_mean(arg.attrs["name"], declared)
                listed = ", ".join(sorted(declared)) or "none"
                raise self._error(
                    arg, f"{path} declares no argument '{arg.attrs['name']}'{hint} (it declares: {listed})"
                )
        self.session.note_file(str(path))
        origin = f"the include at {self.file}:{element.line}"
        stack = (*self.stack, path.resolve())
        _FileEvaluator(self.session, str(path), passed, stack, origin).run(root, frame.namespace)

    def _load_include(self, element: _Element, path: Path) -> _Element:
        if path.suffix in (".py", ".yaml", ".yml"):
            raise self._error(element, f"cannot include {path}: only XML launch files are supported")
        if path.resolve() in self.stack:
            chain = " -> ".join(str(p) for p in (*self.stack, path.resolve()))
            raise self._error(element, f"include cycle: {chain}")
        if len(self.stack) >= MAX_INCLUDE_DEPTH:
            raise self._error(element, f"includes are nested more than {MAX_INCLUDE_DEPTH} deep")
        self.session.files_read += 1
        if self.session.files_read > MAX_FILES_READ:
            raise self._error(element, f"more than {MAX_FILES_READ} files included in one launch")
        try:
            data = _read_bytes(path)
        except FileNotFoundError:
            raise self._error(element, f"included file not found: {path}") from None
        except OSError as err:
            raise self._error(element, f"cannot read included file {path}: {err.strerror}") from None
        return _load_tree(data, str(path))


def _read_bytes(path: Path) -> bytes:
    with path.open("rb") as stream:
        return stream.read(MAX_FILE_BYTES + 1)  # one byte over is enough to refuse it


# --- Public API -----------------------------------------------------------------------------


def parse_launch_file(
    path: str | os.PathLike[str],
    *,
    args: Mapping[str, str] = _NO_ARGS,
    find_package_share: FindPackageShare,
    environ: Mapping[str, str] | None = None,
) -> LaunchDescription:
    """Parse a launch XML file and the files it includes into one flat ``LaunchDescription``.

    ``args`` plays the role of ``ros2 launch ... name:=value``; every name must be declared by
    the file. ``environ`` (default ``os.environ``) answers ``$(env ...)``. Raises
    ``LaunchFileError`` naming the file and line of the first problem.
    """
    file = os.fspath(path)
    try:
        data = _read_bytes(Path(file))
    except FileNotFoundError:
        raise LaunchFileError(file, 0, "launch file not found") from None
    except OSError as err:
        raise LaunchFileError(file, 0, f"cannot read launch file: {err.strerror}") from None
    return _parse(_load_tree(data, file), file, args, find_package_share, environ)


def parse_launch_string(
    text: str,
    *,
    filename: str = "<string>",
    args: Mapping[str, str] = _NO_ARGS,
    find_package_share: FindPackageShare,
    environ: Mapping[str, str] | None = None,
) -> LaunchDescription:
    """Parse launch XML held in memory; ``filename`` names it in errors and anchors relative includes."""
    return _parse(
        _load_tree(text.encode("utf-8"), filename, "utf-8"), filename, args, find_package_share, environ
    )


def _parse(
    root: _Element,
    file: str,
    args: Mapping[str, str],
    find_package_share: FindPackageShare,
    environ: Mapping[str, str] | None,
) -> LaunchDescription:
    declared = _declared_names(root)
    for name in args:
        if name not in declared:
            hint = _did_you_mean(name, declared)
            raise LaunchFileError(
                file, 0, f"argument '{name}' was given but the file declares no such argument{hint}"
            )
    session = _Session(find_package_share, os.environ if environ is None else environ)
    session.note_file(file)
    evaluator = _FileEvaluator(session, file, dict(args), (Path(file).resolve(),), "the caller")
    values = evaluator.run(root, None)
    return LaunchDescription(tuple(session.nodes), MappingProxyType(dict(values)), tuple(session.files))
