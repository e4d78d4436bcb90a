"""A package's executables as its build files declare them, read without running anything.

ament_python: the ``console_scripts`` of ``setup.py`` (the ``entry_points={...}`` literal given to
``setup()``, found in the parsed file) and of ``setup.cfg`` (``[options.entry_points]``), each
``name = package.module:function``. ament_cmake: the files of ``install(PROGRAMS ...)`` in
``CMakeLists.txt``, named by their file name (or ``RENAME``). A declaration that cannot be read is
a :class:`WorkspaceError` naming the file and line.
"""

from __future__ import annotations

import ast
import configparser
import re
from dataclasses import dataclass
from pathlib import Path

from node_runtime.ament.manifest import WorkspaceError

SCRIPT = re.compile(r"^\s*([^=\s]+)\s*=\s*([\w.]+)\s*:\s*([\w.]+)\s*(\[[^\]]*\])?\s*$")
INSTALL = re.compile(r"\binstall\s*\(([^)]*)\)", re.IGNORECASE)
PROGRAM_END = {
    "DESTINATION",
    "PERMISSIONS",
    "CONFIGURATIONS",
    "COMPONENT",
    "RENAME",
    "OPTIONAL",
    "EXCLUDE_FROM_ALL",
    "TYPE",
}


@dataclass(frozen=True)
class ConsoleScript:
    name: str
    module: str
    function: str
    declared_at: str  # "setup.py:LINE", where a wrong module or function is reported


@dataclass(frozen=True)
class EntryPoint:
    """A console script: ``name = module:function``, declared at ``declared_at``, of the package in ``root``."""

    root: Path
    module: str
    function: str
    name: str
    declared_at: str

    def argv(self) -> list[str]:
        return [
            "--entry-point",
            str(self.root),
            f"{self.module}:{self.function}",
            self.name,
            self.declared_at,
        ]


def parse_script(text: str, where: str) -> ConsoleScript:
    match = SCRIPT.match(text)
    if match is None:
        raise WorkspaceError(where, f"console script {text!r} is not 'name = package.module:function'")
    return ConsoleScript(match[1], match[2], match[3], where)


def _string(node: ast.expr, constants: dict[str, str]) -> str | None:
    """A string literal, a module string constant (``package_name``), or ``+``/f-strings of them."""
    if isinstance(node, ast.Constant):
        return node.value if isinstance(node.value, str) else None
    if isinstance(node, ast.Name):
        return constants.get(node.id)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _string(node.left, constants), _string(node.right, constants)
        return left + right if left is not None and right is not None else None
    if isinstance(node, ast.JoinedStr):
        parts = [_string(v.value if isinstance(v, ast.FormattedValue) else v, constants) for v in node.values]
        return "".join(p for p in parts if p is not None) if None not in parts else None
    return None


def _module_values(tree: ast.Module) -> dict[str, ast.expr]:
    return {
        node.targets[0].id: node.value
        for node in tree.body
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name)
    }


def _setup_call(tree: ast.Module) -> ast.Call | None:
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            name = (
                func.id
                if isinstance(func, ast.Name)
                else func.attr
                if isinstance(func, ast.Attribute)
                else ""
            )
            if name == "setup":
                return node
    return None


def setup_py_scripts(path: Path) -> list[ConsoleScript]:
    try:
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    except SyntaxError as exc:
        raise WorkspaceError(f"{path}:{exc.lineno}", f"SyntaxError: {exc.msg}") from None
    values = _module_values(tree)
    constants = {
        name: v.value
        for name, v in values.items()
        if isinstance(v, ast.Constant) and isinstance(v.value, str)
    }
    call = _setup_call(tree)
    keyword = next((k for k in call.keywords if k.arg == "entry_points"), None) if call else None
    if keyword is None:
        return []
    points = (
        values.get(keyword.value.id, keyword.value) if isinstance(keyword.value, ast.Name) else keyword.value
    )
    if not isinstance(points, ast.Dict):
        raise WorkspaceError(
            f"{path}:{keyword.value.lineno}",
            "entry_points is not a literal dict (the lab reads setup.py without running it)",
        )
    scripts = next(
        (
            v
            for k, v in zip(points.keys, points.values, strict=True)
            if k is not None and _string(k, constants) == "console_scripts"
        ),
        None,
    )
    if scripts is None:
        return []
    if isinstance(scripts, ast.Name):
        scripts = values.get(scripts.id, scripts)
    if not isinstance(scripts, ast.List | ast.Tuple):
        raise WorkspaceError(f"{path}:{scripts.lineno}", "console_scripts is not a literal list of strings")
    out = []
    for item in scripts.elts:
        text = _string(item, constants)
        if text is None:
            raise WorkspaceError(f"{path}:{item.lineno}", "a console script is not a string literal")
        out.append(parse_script(text, f"{path}:{item.lineno}"))
    return out


def setup_cfg_scripts(path: Path) -> list[ConsoleScript]:
    parser = configparser.ConfigParser(interpolation=None)
    text = path.read_text(encoding="utf-8")
    try:
        parser.read_string(text, source=str(path))
    except configparser.Error as exc:
        line = getattr(exc, "lineno", None)
        raise WorkspaceError(
            f"{path}:{line}" if line else str(path), f"setup.cfg does not parse: {exc}"
        ) from None
    raw = parser.get("options.entry_points", "console_scripts", fallback="")
    lines = text.splitlines()
    out = []
    for script in filter(None, (s.strip() for s in raw.splitlines())):
        number = next((i for i, line in enumerate(lines, 1) if line.strip() == script), None)
        out.append(parse_script(script, f"{path}:{number}" if number else str(path)))
    return out


def _strip_comments(text: str) -> str:
    return re.sub(r"#[^\n]*", lambda m: " " * len(m[0]), text)


def cmake_programs(path: Path, project: str) -> dict[str, tuple[Path, str]]:
    """Executable name → (the installed file, "CMakeLists.txt:LINE") for ``install(PROGRAMS ...)``."""
    text = _strip_comments(path.read_text(encoding="utf-8"))
    programs: dict[str, tuple[Path, str]] = {}
    for match in INSTALL.finditer(text):
        words = [w.strip('"').replace("${PROJECT_NAME}", project) for w in match[1].split()]
        if not words or words[0].upper() != "PROGRAMS":
            continue
        line = text.count("\n", 0, match.start()) + 1
        files = []
        for word in words[1:]:
            if word.upper() in PROGRAM_END:
                break
            files.append(word)
        upper = [w.upper() for w in words]
        rename = words[upper.index("RENAME") + 1] if "RENAME" in upper[:-1] else None
        for file in files:
            source = path.parent / file
            programs[rename if rename and len(files) == 1 else source.name] = (source, f"{path}:{line}")
    return programs
