"""Write the message classes from the interface definitions: ``python -m node_runtime.msgs.generate``.

As rosidl generates Python classes from ``.msg`` files, this writes one module per package
under ``node_runtime/msgs/generated/`` with a class per message and service, and the package a
student's node imports (``client/<pkg>/msg``, ``srv``, ``action``). The classes only declare
what a reader and mypy need to see (field names and Python types, constants, a typed
constructor); their behaviour, defaults and checks come from the definitions at import time,
so the definitions stay the single source: the lab's own (``interfaces/``) and ROS 2's, taken
from its wheels on PyPI at set-up (``ros_interfaces/``, node_runtime/ros_wheels.py). A test checks the
files are current.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from pathlib import Path

from node_runtime.msgs._field import ARRAY_TYPECODES
from node_runtime.msgs.definitions import INTERFACES_DIR, Definitions, lab_definitions
from node_runtime.msgs.idl import FLOAT_TYPES, INT_RANGES, STRING_TYPES, FieldSpec, MessageSpec

LINE_LENGTH = 110  # ruff's, in pyproject.toml
GENERATED_DIR = Path(__file__).resolve().parent / "generated"
CLIENT_DIR = Path(__file__).resolve().parents[2] / "client"
HEADER = (
    '"""{package}: generated from {source} by `python -m node_runtime.msgs.generate`; do not edit."""\n\n'
)
ROS_SOURCE = "ROS 2's definitions (the wheels node_runtime/msgs/ros_packages.txt pins)"
CLIENT_MODULE = (
    "from node_runtime.msgs.generated.{package} import *  # noqa: F403\n"
    "from node_runtime.msgs.generated.{package} import __all__ as __all__\n"
)
NUMPY_SCALARS = {
    "bool": "np.bool_",
    "byte": "np.uint8",
    "char": "np.uint8",
    "float32": "np.float32",
    "float64": "np.float64",
    **{k: f"np.{k}" for k in INT_RANGES if k not in ("byte", "char")},
}


def _class_name(type_name: str) -> str:
    return type_name.rsplit("/", 1)[1]


def _scalar_python_type(base: str) -> str:
    if base == "bool":
        return "bool"
    if base in INT_RANGES:
        return "int"
    if base in FLOAT_TYPES:
        return "float"
    if base in STRING_TYPES:
        return "str"
    return _class_name(base)


def _python_types(field: FieldSpec) -> tuple[str, str]:
    """(the attribute's type, the constructor argument's type)."""
    if not field.is_array:
        t = _scalar_python_type(field.base)
        return t, t
    if field.is_sequence and field.base == "bool":
        return "list[bool]", "Sequence[bool] | npt.NDArray[Any]"
    if field.is_sequence and field.base in ARRAY_TYPECODES:
        element = _scalar_python_type(field.base)
        return f"{element.capitalize()}Array", f"Sequence[{element}] | npt.NDArray[Any]"
    if field.is_primitive and field.base not in STRING_TYPES:
        element = _scalar_python_type(field.base)
        return f"npt.NDArray[{NUMPY_SCALARS[field.base]}]", f"Sequence[{element}] | npt.NDArray[Any]"
    element = _scalar_python_type(field.base)
    return f"list[{element}]", f"Sequence[{element}]"


def _doc(spec: MessageSpec) -> str:
    first = next((line.lstrip("# ").strip() for line in spec.text.splitlines() if line.startswith("#")), "")
    first = first.replace("\\", "/").replace('"', "'")  # a docstring's text as it is
    return f"{spec.name}: {first}" if first else spec.name


def _message_class(spec: MessageSpec) -> list[str]:
    name = _class_name(spec.name)
    header = f'class {name}(Message, type_name="{spec.name}"):'
    if len(header) > LINE_LENGTH:  # as ruff format wraps it
        header = f'class {name}(\n    Message, type_name="{spec.name}"\n):'
    lines = [header, f'    """{_doc(spec)}"""', ""]
    if len(spec.fields) == 1:
        lines.append(f'    __slots__ = ("{spec.fields[0].name}",)')
    elif spec.fields:
        lines += ["    __slots__ = (", *(f'        "{f.name}",' for f in spec.fields), "    )"]
    else:
        lines.append("    __slots__ = ()")
    for constant in spec.constants:
        lines.append(f"    {constant.name}: ClassVar[{_scalar_python_type(constant.base)}]")
    for field in spec.fields:
        lines.append(f"    {field.name}: {_python_types(field)[0]}")
    if spec.fields:
        params = [f"            {f.name}: {_python_types(f)[1]} = ...," for f in spec.fields]
        lines += [
            "",
            "    if TYPE_CHECKING:",
            "",
            "        def __init__(",
            "            self,",
            "            *,",
            *params,
            "        ) -> None: ...",
        ]
    return lines


def _service_class(name: str) -> list[str]:
    short = _class_name(name)
    return [
        f'class {short}(Service, type_name="{name}"):',
        f'    """{name}: call with a {short}.Request, answered with a {short}.Response."""',
        "",
        f"    Request = {short}_Request",
        f"    Response = {short}_Response",
    ]


def _action_class(name: str) -> list[str]:
    short = _class_name(name)
    return [
        f'class {short}(Action, type_name="{name}"):',
        f'    """{name}: a {short}.Goal, answered with a {short}.Result, {short}.Feedback meanwhile."""',
        "",
        f"    Goal = {short}_Goal",
        f"    Result = {short}_Result",
        f"    Feedback = {short}_Feedback",
        "",
        "    class Impl:",
        f"        SendGoalService = {short}_SendGoal",
        f"        GetResultService = {short}_GetResult",
        f"        FeedbackMessage = {short}_FeedbackMessage",
        "        CancelGoalService = CancelGoal",
        "        GoalStatusMessage = GoalStatusArray",
    ]


def _ordered(specs: Iterable[MessageSpec]) -> list[MessageSpec]:
    """Dependencies first, so that a class exists before a class that nests it."""
    pending = {s.name: s for s in specs}
    done: list[MessageSpec] = []

    def visit(spec: MessageSpec) -> None:
        if spec.name not in pending:
            return
        del pending[spec.name]
        for dep in spec.dependencies():
            if dep in pending:
                visit(pending[dep])
        done.append(spec)

    for spec in list(pending.values()):
        visit(spec)
    return done


def package_module(package: str, definitions: Definitions) -> str:
    """The source of ``generated/<package>.py``."""
    messages = [s for n, s in definitions.messages.items() if n.startswith(package + "/")]
    services = [s for n, s in definitions.services.items() if n.startswith(package + "/")]
    actions = [a for n, a in definitions.actions.items() if n.startswith(package + "/")]
    specs = _ordered(messages + [p for s in services for p in (s.request, s.response)])
    foreign = {d for s in specs for d in s.dependencies() if not d.startswith(package + "/")}
    if actions:
        foreign |= {"action_msgs/srv/CancelGoal", "action_msgs/msg/GoalStatusArray"}
    body: list[str] = []
    for spec in specs:
        body += ["", "", *_message_class(spec)]
    for service in services:
        body += ["", "", *_service_class(service.name)]
    for action in actions:
        body += ["", "", *_action_class(action.name)]
    text = "\n".join(body)
    imports = ["from __future__ import annotations", ""]
    typing_names = ["Any"] if "Any]" in text else []
    typing_names += ["ClassVar"] if "ClassVar[" in text else []
    if "Sequence[" in text:
        imports.append("from collections.abc import Sequence")
    imports.append(f"from typing import {', '.join(['TYPE_CHECKING', *typing_names])}")
    imports.append("")
    numpy = ["    import numpy as np"] if "np." in text else []
    numpy += ["    import numpy.typing as npt"] if "npt." in text else []
    if numpy:  # for the annotations only: numpy loads at the first fixed-size numeric array
        imports += ["if TYPE_CHECKING:", *numpy, ""]
    if actions:
        imports.append("from node_runtime.msgs._action import Action")
    bases = ["Message"] + (["Service"] if services else [])
    imports.append(f"from node_runtime.msgs._base import {', '.join(bases)}")
    arrays = [a for a in ("FloatArray", "IntArray") if f": {a}" in text]
    if arrays:
        imports.append(f"from node_runtime.msgs._field import {', '.join(arrays)}")
    by_package: dict[str, list[str]] = {}
    for dep in sorted(foreign):
        by_package.setdefault(dep.split("/")[0], []).append(_class_name(dep))
    for pkg, names in sorted(by_package.items()):
        line = f"from node_runtime.msgs.generated.{pkg} import {', '.join(sorted(set(names)))}"
        if len(line) > LINE_LENGTH:  # as ruff's isort wraps it
            line = (
                f"from node_runtime.msgs.generated.{pkg} import (\n"
                + "".join(f"    {n},\n" for n in sorted(set(names)))
                + ")"
            )
        imports.append(line)
    names = [
        _class_name(n)
        for n in [s.name for s in specs] + [s.name for s in services] + [a.name for a in actions]
    ]
    exports = "\n\n__all__ = [\n" + "".join(f'    "{n}",\n' for n in sorted(names)) + "]\n"
    own = (INTERFACES_DIR / package).is_dir()
    source = f"node_runtime/msgs/interfaces/{package}" if own else ROS_SOURCE
    return HEADER.format(package=package, source=source) + "\n".join(imports) + "\n" + text + "\n" + exports


def packages(definitions: Definitions) -> list[str]:
    return sorted({n.split("/")[0] for n in list(definitions.messages) + list(definitions.services)})


def type_hashes_module(definitions: Definitions) -> str:
    """The RIHS01 hash of every type (and service part) in ``definitions``, as a table: a node
    process looks its types' hashes up there instead of building rosbags' typestore."""
    from node_runtime.msgs.wire import computed_type_hashes  # rosbags: only to write the table

    rows = "".join(f'    "{name}": "{value}",\n' for name, value in computed_type_hashes(definitions).items())
    return (
        '"""RIHS01 type hashes of the lab\'s interfaces: generated from node_runtime/msgs/interfaces and '
        f'{ROS_SOURCE} by `python -m node_runtime.msgs.generate`; do not edit."""\n\n'
        "# fmt: off\nTYPE_HASHES: dict[str, str] = {\n" + rows + "}\n# fmt: on\n"
    )


def generated_files(definitions: Definitions | None = None) -> dict[Path, str]:
    """Every generated file's path and text (the package modules, their ``__init__`` and the
    table of type hashes)."""
    definitions = definitions or lab_definitions()
    files = {GENERATED_DIR / f"{pkg}.py": package_module(pkg, definitions) for pkg in packages(definitions)}
    names = packages(definitions)
    files[GENERATED_DIR / "__init__.py"] = (
        '"""The message and service classes, one module per ROS package (see node_runtime/msgs/generate.py);\n'
        "a module is imported when one of its types is first asked for (node_runtime/msgs/_base.py's\n"
        'load_generated), so a process declares only the classes it uses."""\n\n'
        + "PACKAGES = (\n"
        + "".join(f'    "{pkg}",\n' for pkg in names)
        + ")\n"
    )
    files[GENERATED_DIR / "type_hashes.py"] = type_hashes_module(definitions)
    files.update(client_files(definitions))
    return files


def client_files(definitions: Definitions) -> dict[Path, str]:
    """``client/<pkg>/__init__.py`` and its ``msg``, ``srv`` and ``action`` modules, each giving the
    package's classes, as rosidl's Python packages are imported (``from std_msgs.msg import String``)."""
    kinds: dict[str, set[str]] = {}
    for name in [*definitions.messages, *definitions.services, *definitions.actions]:
        package, kind, _ = name.split("/")
        kinds.setdefault(package, set()).add(kind)
    files = {}
    for package, found in kinds.items():
        files[CLIENT_DIR / package / "__init__.py"] = "\n"
        for kind in sorted(found):
            files[CLIENT_DIR / package / kind / "__init__.py"] = CLIENT_MODULE.format(package=package)
    return files


def main() -> int:
    files = generated_files()
    for path, text in files.items():
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    print(f"wrote {len(files)} files to {GENERATED_DIR} and {CLIENT_DIR}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
