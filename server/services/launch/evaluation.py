"""Evaluate a checked launch tree: substitutions and conditions, includes (each included file
has its own argument scope) and the nodes, collected in document order. Nothing is executed:
the result is plain data for the launcher.
"""

from __future__ import annotations

import os
import shlex
from collections import ChainMap
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

from node_runtime.params_file import ParamsFile
from server.services.launch.description import (
    CommandAction,
    LaunchDescription,
    LaunchFileError,
    NodeAction,
    ParamValue,
    SourceLocation,
)
from server.services.launch.executables import command, timer_frame
from server.services.launch.expressions import evaluate_expression
from server.services.launch.frontends import load_frontend_tree
from server.services.launch.param_files import load_param_file
from server.services.launch.substitutions import SubstitutionError, arity, package_not_found, substitute
from server.services.launch.values import OUTPUTS, join_namespace, parse_bool, typed_param
from server.services.launch.xml_tree import ACTIONS, Element, declared_names, did_you_mean, read_bytes

MAX_INCLUDE_DEPTH = 32
MAX_FILES_READ = 256  # counted with repetition: a diamond of includes doubles the work per level

FindPackageShare = Callable[[str], Path]
"""Maps a package name to its share directory; raises ``LookupError`` for an unknown package."""
IncludePython = Callable[["Session", Path, Mapping[str, str], "str | None", tuple[Path, ...]], None]
"""Evaluates a Python launch file into the session: its path, the arguments passed, the namespace
pushed where it is included, and the chain of files that include it (server/services/launch/python_launch.py)."""


@dataclass
class Session:
    find_package_share: FindPackageShare
    environ: Mapping[str, str]
    # Where included files may lie (resolved, links followed); None: anywhere. A file elsewhere is
    # refused as a missing one is, so the answer tells nothing of what exists outside.
    roots: tuple[Path, ...] | None = None
    include_python: IncludePython | None = None  # None: a Python launch file cannot be included
    nodes: list[NodeAction] = field(default_factory=list)
    files: list[str] = field(default_factory=list)
    messages: list[str] = field(default_factory=list)  # lines to show with the launch (LogInfo's)
    commands: list[CommandAction] = field(default_factory=list)
    files_read: int = 1

    def may_read(self, path: Path) -> bool:
        if self.roots is None:
            return True
        try:
            resolved = path.resolve()
        except (OSError, RuntimeError):  # a link loop, a name too long
            return False
        return any(resolved.is_relative_to(root.resolve()) for root in self.roots)

    def note_file(self, file: str) -> None:
        if file not in self.files:
            self.files.append(file)

    def description(self, args: Mapping[str, str]) -> LaunchDescription:
        return LaunchDescription(
            tuple(self.nodes),
            MappingProxyType(dict(args)),
            tuple(self.files),
            tuple(self.messages),
            tuple(self.commands),
        )


@dataclass
class _Frame:
    """What a group sees: its variables (scoped by ChainMap) and its pushed namespace."""

    variables: ChainMap[str, str]
    namespace: str | None
    delay_s: float = 0.0  # inside a <timer>: what its nodes and commands wait before they start


class FileEvaluator:
    """Evaluates one file's actions; ``origin`` names who passed ``passed`` (for error messages)."""

    def __init__(
        self,
        session: Session,
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

    def run(self, root: Element, namespace: str | None) -> dict[str, str]:
        self._run_actions(root, _Frame(ChainMap({}), namespace))
        return self.declared

    def _error(self, element: Element, problem: str) -> LaunchFileError:
        return LaunchFileError(self.file, element.line, problem)

    def _run_actions(self, parent: Element, frame: _Frame) -> None:
        handlers: Mapping[str, Callable[[Element, _Frame], None]] = {
            "arg": self._run_arg,
            "let": self._run_let,
            "node": self._run_node,
            "include": self._run_include,
            "group": self._run_group,
            "push-ros-namespace": self._run_push_namespace,
            "executable": lambda element, frame: self.session.commands.append(command(self, element, frame)),
            "timer": lambda element, frame: self._run_actions(element, timer_frame(self, element, frame)),
        }
        for element in parent.children:
            if self._active(element, frame):
                handlers[ACTIONS[element.tag]](element, frame)

    # -- attributes

    def _sub(self, element: Element, attr: str, frame: _Frame) -> str:
        raw = element.attrs[attr]

        def resolve(name: str, args: list[str]) -> str:
            return self._resolve(name, args, frame)

        try:
            return substitute(raw, resolve)
        except SubstitutionError as err:
            raise self._error(element, f'in {attr}="{raw}": {err}') from None

    def _optional(self, element: Element, attr: str, frame: _Frame) -> str | None:
        return self._sub(element, attr, frame) if attr in element.attrs else None

    def _resolve(self, name: str, args: list[str], frame: _Frame) -> str:
        if name == "var":
            arity(name, args, 1, 1)
            if args[0] not in frame.variables:
                hint = did_you_mean(args[0], frame.variables) or " (declare it with <arg> above this line)"
                raise SubstitutionError(f"no argument or variable '{args[0]}' is defined here{hint}")
            return frame.variables[args[0]]
        if name == "find-pkg-share":
            arity(name, args, 1, 1)
            try:
                return str(self.session.find_package_share(args[0]))
            except LookupError as err:
                raise SubstitutionError(package_not_found(args[0], err)) from None
        if name == "env":
            arity(name, args, 1, 2)
            value = self.session.environ.get(args[0])
            if value is None and len(args) == 1:
                raise SubstitutionError(f"environment variable '{args[0]}' is not set (no default given)")
            return value if value is not None else args[1]
        if name == "eval":  # its quoted argument's own substitutions first, as ROS 2 does
            arity(name, args, 1, 1)
            return evaluate_expression(substitute(args[0], lambda n, a: self._resolve(n, a, frame)))
        arity(name, args, 0, 0)  # dirname
        return str(Path(self.file).parent)

    def _active(self, element: Element, frame: _Frame) -> bool:
        for attr, wanted in (("if", True), ("unless", False)):
            if attr in element.attrs:
                value = self._sub(element, attr, frame)
                truth = parse_bool(value)
                if truth is None:
                    raise self._error(
                        element, f'{attr}="{value}" is not a condition: use true, false, 1 or 0'
                    )
                return truth == wanted
        return True

    # -- actions

    def _run_arg(self, element: Element, frame: _Frame) -> None:
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

    def _run_let(self, element: Element, frame: _Frame) -> None:
        frame.variables[element.attrs["name"]] = self._sub(element, "value", frame)

    def _run_group(self, element: Element, frame: _Frame) -> None:
        self._run_actions(element, _Frame(frame.variables.new_child(), frame.namespace, frame.delay_s))

    def _run_push_namespace(self, element: Element, frame: _Frame) -> None:
        frame.namespace = join_namespace(frame.namespace, self._sub(element, "namespace", frame))

    def _run_node(self, element: Element, frame: _Frame) -> None:
        pkg = self._sub(element, "pkg", frame)
        executable = self._sub(element, "exec" if "exec" in element.attrs else "type", frame)
        if not pkg or not executable:
            raise self._error(element, "<node> has an empty pkg= or exec=")
        node_ns = self._optional(element, "namespace" if "namespace" in element.attrs else "ns", frame)
        output = self._optional(element, "output", frame)
        if output is not None and output not in OUTPUTS:
            raise self._error(element, f'output="{output}" is not one of {", ".join(OUTPUTS)}')
        on_exit = self._optional(element, "on_exit", frame)
        if on_exit not in (None, "shutdown"):
            raise self._error(element, f'on_exit="{on_exit}" is not supported; the only value is "shutdown"')
        parameters: list[tuple[str, ParamValue]] = []
        files: list[ParamsFile] = []
        self._collect_params(element, frame, "", parameters, {}, files)
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
                namespace=frame.namespace if node_ns is None else join_namespace(frame.namespace, node_ns),
                output=output,
                respawn=self._respawn(element, frame),
                respawn_delay_s=self._respawn_delay_s(element, frame),
                parameters=tuple(parameters),
                remappings=remappings,
                location=SourceLocation(self.file, element.line),
                shutdown_on_exit=on_exit == "shutdown",
                parameter_files=tuple(files),
                arguments=self._words(element, "args", frame),
                ros_arguments=self._words(element, "ros_args", frame),
                start_delay_s=frame.delay_s,
            )
        )

    def _words(self, element: Element, attr: str, frame: _Frame) -> tuple[str, ...]:
        """``args="a 'b c'"``: the node's command-line words, split as a shell would."""
        text = self._optional(element, attr, frame)
        try:
            return tuple(shlex.split(text)) if text else ()
        except ValueError as err:
            raise self._error(element, f'{attr}="{text}": {err}') from None

    def _respawn(self, element: Element, frame: _Frame) -> bool:
        text = self._optional(element, "respawn", frame)
        value = False if text is None else parse_bool(text)
        if value is None:
            raise self._error(element, f'respawn="{text}" is not a boolean: use true or false')
        return value

    def _respawn_delay_s(self, element: Element, frame: _Frame) -> float:
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
        parent: Element,
        frame: _Frame,
        prefix: str,
        out: list[tuple[str, ParamValue]],
        seen: dict[str, int],
        files: list[ParamsFile],
    ) -> None:
        for child in parent.children:
            if child.tag != "param":
                continue
            if "from" in child.attrs:
                if prefix:
                    raise self._error(
                        child,
                        "<param from=...> loads a file for the whole node: "
                        "put it in <node>, not in a <param>",
                    )
                files.append(self._read_param_file(child, frame))
                continue
            name = prefix + self._sub(child, "name", frame)
            if child.children:
                self._collect_params(child, frame, name + ".", out, seen, files)
                continue
            if name in seen:
                raise self._error(child, f"parameter '{name}' is set twice (first at line {seen[name]})")
            seen[name] = child.line
            try:
                out.append((name, typed_param(self._sub(child, "value", frame))))
            except ValueError as err:
                raise self._error(child, f"parameter '{name}': {err}") from None

    def _read_param_file(self, element: Element, frame: _Frame) -> ParamsFile:
        return read_param_file(self.session, self._sub(element, "from", frame), self.file, element.line)

    def _run_include(self, element: Element, frame: _Frame) -> None:
        path = Path(self._sub(element, "file", frame))
        if not path.is_absolute():
            path = Path(self.file).parent / path
        passed: dict[str, str] = {}
        for arg in element.children:
            if arg.attrs["name"] in passed:
                raise self._error(arg, f"argument '{arg.attrs['name']}' is passed twice")
            passed[arg.attrs["name"]] = self._sub(arg, "value", frame)
        if is_python(path):
            include_python(self.session, path, passed, frame.namespace, self.stack, (self.file, element.line))
            return
        root = load_include(self.session, self.stack, path, (self.file, element.line))
        declared = declared_names(root)
        for arg in element.children:
            if arg.attrs["name"] not in declared:
                hint = did_you_mean(arg.attrs["name"], declared)
                listed = ", ".join(sorted(declared)) or "none"
                raise self._error(
                    arg, f"{path} declares no argument '{arg.attrs['name']}'{hint} (it declares: {listed})"
                )
        self.session.note_file(str(path))
        origin = f"the include at {self.file}:{element.line}"
        stack = (*self.stack, path.resolve())
        FileEvaluator(self.session, str(path), passed, stack, origin).run(root, frame.namespace)


def read_param_file(session: Session, text: str, file: str, line: int) -> ParamsFile:
    """The parameters file ``text`` names, for a node written at ``file``:``line``."""
    session.files_read += 1
    if session.files_read > MAX_FILES_READ:
        raise LaunchFileError(file, line, f"more than {MAX_FILES_READ} files read in one launch")
    loaded = load_param_file(text, file, session.may_read)
    if isinstance(loaded, str):
        raise LaunchFileError(file, line, loaded)
    session.note_file(loaded.path)
    return loaded


def is_python(path: Path) -> bool:
    """A Python launch file, by its name, as ``ros2 launch`` tells (``x.launch.py``, ``x_launch.py``)."""
    return path.suffix == ".py"


def _may_include(session: Session, stack: tuple[Path, ...], path: Path, at: tuple[str, int]) -> None:
    if path.resolve() in stack:
        chain = " -> ".join(str(p) for p in (*stack, path.resolve()))
        raise LaunchFileError(*at, f"include cycle: {chain}")
    if len(stack) >= MAX_INCLUDE_DEPTH:
        raise LaunchFileError(*at, f"includes are nested more than {MAX_INCLUDE_DEPTH} deep")
    session.files_read += 1
    if session.files_read > MAX_FILES_READ:
        raise LaunchFileError(*at, f"more than {MAX_FILES_READ} files included in one launch")
    if not session.may_read(path) or (is_python(path) and not path.is_file()):
        raise LaunchFileError(*at, f"included file not found: {path}")


def load_include(session: Session, stack: tuple[Path, ...], path: Path, at: tuple[str, int]) -> Element:
    """The checked tree of an XML or YAML file included at ``at`` (file and line)."""
    _may_include(session, stack, path, at)
    try:
        data = read_bytes(path)
    except FileNotFoundError:
        raise LaunchFileError(*at, f"included file not found: {path}") from None
    except OSError as err:
        raise LaunchFileError(*at, f"cannot read included file {path}: {err.strerror}") from None
    return load_frontend_tree(data, str(path))


def include_python(
    session: Session,
    path: Path,
    passed: Mapping[str, str],
    namespace: str | None,
    stack: tuple[Path, ...],
    at: tuple[str, int],
) -> None:
    """A Python launch file included at ``at``, evaluated by ``session.include_python``."""
    if session.include_python is None:
        raise LaunchFileError(*at, f"cannot include {path}: Python launch files are not evaluated here")
    _may_include(session, stack, path, at)
    session.note_file(str(path))
    session.include_python(session, path, passed, namespace, (*stack, path.resolve()))


def evaluate(
    root: Element,
    file: str,
    args: Mapping[str, str],
    find_package_share: FindPackageShare,
    environ: Mapping[str, str] | None,
    roots: tuple[Path, ...] | None = None,
    include_python: IncludePython | None = None,
) -> LaunchDescription:
    """Evaluate a checked tree from ``file`` with the caller's ``args`` into one flat description;
    with ``roots``, an include outside them is refused as a missing file."""
    declared = declared_names(root)
    for name in args:
        if name not in declared:
            hint = did_you_mean(name, declared)
            raise LaunchFileError(
                file, 0, f"argument '{name}' was given but the file declares no such argument{hint}"
            )
    session = Session(find_package_share, os.environ if environ is None else environ, roots, include_python)
    session.note_file(file)
    evaluator = FileEvaluator(session, file, dict(args), (Path(file).resolve(),), "the caller")
    values = evaluator.run(root, None)
    return session.description(values)
