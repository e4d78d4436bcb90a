"""The layer check: every import of every module, against the order docs/architecture.md writes down.

A module belongs to the unit with the longest dotted prefix of its name (``node_runtime.bus``,
``api``, ``server.world``). An import stays inside its layer or goes to a lower one; one that goes up a
layer is a violation. Inside a layer, the parts (each unit's packages and modules one level down:
``server.world.lab``, ``server.world.checkpoints``) may import one another, but never in a circle:
an import cycle between two parts of a layer is a violation too. Every
import counts, wherever it is written (at the top, inside a function, under ``TYPE_CHECKING``,
relative or absolute), and so does what Python runs for it: ``import a.b.c`` runs ``a`` and
``a.b`` too, and a module's own packages run before it.
"""

from __future__ import annotations

import ast
import sys
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from functools import cache
from pathlib import Path


@dataclass(frozen=True)
class Layer:
    name: str
    units: tuple[str, ...]


@dataclass(frozen=True)
class Import:
    """``source`` (a module) runs ``target`` (a module of the tree), at ``line`` of its file (0: it
    is a package that Python runs before ``source``)."""

    source: str
    target: str
    path: Path
    line: int


@dataclass(frozen=True)
class Violation:
    edge: Import
    source_layer: str
    target_layer: str
    why: str

    def __str__(self) -> str:
        e = self.edge
        where = f"{e.path}:{e.line}" if e.line else f"{e.path} (its package)"
        return (
            f"{where}: {e.source} ({self.source_layer}) imports {e.target} ({self.target_layer}): {self.why}"
        )


def parse_layers(text: str) -> list[Layer]:
    """The layers of the fenced ``layers`` block of a Markdown text, highest first: one layer a line,
    ``name: unit unit ...``."""
    lines = text.splitlines()
    try:
        start = lines.index("```layers") + 1
        end = lines.index("```", start)
    except ValueError:
        raise ValueError("no ```layers block") from None
    layers = []
    for line in lines[start:end]:
        if not line.strip():
            continue
        name, sep, units = line.partition(":")
        if not sep or not units.split():
            raise ValueError(f"a layer line is 'name: unit unit ...', not {line!r}")
        layers.append(Layer(name.strip(), tuple(units.split())))
    return layers


def find_modules(root: Path, packages: Iterable[str]) -> dict[str, tuple[Path, bool]]:
    """Every module of ``packages`` under ``root``: its dotted name → (its file, whether a package)."""
    found: dict[str, tuple[Path, bool]] = {}
    for top in packages:
        for path in sorted((root / top).rglob("*.py")):
            parts = list(path.relative_to(root).with_suffix("").parts)
            is_package = parts[-1] == "__init__"
            if is_package:
                parts.pop()
            found[".".join(parts)] = (path, is_package)
    return found


def _with_parents(name: str) -> Iterator[str]:
    parts = name.split(".")
    for i in range(1, len(parts) + 1):
        yield ".".join(parts[:i])


def _imported(node: ast.AST, package: str) -> Iterator[tuple[str, list[str]]]:
    """(module, names imported from it) for an import statement; relative ones resolved."""
    if isinstance(node, ast.Import):
        for alias in node.names:
            yield alias.name, []
    elif isinstance(node, ast.ImportFrom):
        if node.level:
            base = package.split(".")
            if node.level - 1 > len(base) - 1:
                raise ValueError(f"relative import beyond the top package in {package}")
            base = base[: len(base) - (node.level - 1)]
            module = ".".join(base + ([node.module] if node.module else []))
        else:
            module = node.module or ""
        yield module, [alias.name for alias in node.names]


def module_imports(modules: dict[str, tuple[Path, bool]]) -> tuple[list[Import], dict[str, set[str]]]:
    """Every import between modules of the tree, and each module's imports from outside it (top
    names: ``numpy``, ``fastapi``)."""
    edges: list[Import] = []
    external: dict[str, set[str]] = {}
    tops = {m.split(".")[0] for m in modules}
    client_tops = {m.split(".")[1] for m in modules if m.startswith("client.") and m.count(".") >= 1}
    for name, (path, is_package) in modules.items():
        package = name if is_package else name.rpartition(".")[0]
        external[name] = set()
        for parent in list(_with_parents(name))[:-1]:  # a module's packages run before it
            if parent in modules:
                edges.append(Import(name, parent, path, 0))
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            for module, names in _imported(node, package):
                if module.split(".")[0] not in tops and f"client.{module}".split(".")[1] in client_tops:
                    module = f"client.{module}"  # client/ is a path root: client/rclpy is rclpy
                targets = [m for m in _with_parents(module) if m in modules]
                targets += [f"{module}.{n}" for n in names if f"{module}.{n}" in modules]
                if not targets and module.split(".")[0] not in {m.split(".")[0] for m in modules}:
                    external[name].add(module.split(".")[0])
                line = getattr(node, "lineno", 0)
                edges.extend(Import(name, t, path, line) for t in targets if t != name)
    return edges, external


@cache
def read_tree(
    root: Path, packages: tuple[str, ...]
) -> tuple[dict[str, tuple[Path, bool]], list[Import], dict[str, set[str]]]:
    """The tree's modules, imports and outside imports, read once per tree (the test reads it often)."""
    modules = find_modules(root, packages)
    edges, external = module_imports(modules)
    return modules, edges, external


def unit_of(module: str, units: Iterable[str]) -> str | None:
    """The unit ``module`` belongs to: the longest unit that is it or a package above it. A unit
    with units inside it (``server``, beside ``node_runtime.bus``) holds only its own ``__init__``, so a
    new module there belongs to no unit until the layers say where it goes."""
    units = list(units)
    owners = [u for u in units if module == u or module.startswith(u + ".")]
    if not owners:
        return None
    owner = max(owners, key=len)
    if owner != module and any(u.startswith(owner + ".") for u in units):
        return None
    return owner


def part_of(module: str, unit: str, layer: Layer) -> str:
    """The part of its layer that ``module`` (of ``unit``) is in: its unit, when the layer lists
    several; in a layer of one folder, that folder's package or module one level down
    (``server.world.checkpoints`` for ``server.world.checkpoints.watcher``)."""
    if module == unit or len(layer.units) > 1:
        return unit
    return unit + "." + module[len(unit) + 1 :].split(".")[0]


def _cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected parts of ``graph`` with more than one node (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in sorted(graph.get(node, ())):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def check(root: Path, layers: list[Layer], packages: Iterable[str]) -> list[Violation]:
    """Every import of ``packages`` (under ``root``) against ``layers`` (highest first): every module
    no unit holds, every import up a layer, and every import cycle between the parts of a layer."""
    rank = {unit: (i, layer.name) for i, layer in enumerate(layers) for unit in layer.units}
    layer_of = {unit: layer for layer in layers for unit in layer.units}
    _, edges, _ = read_tree(root, tuple(packages))
    violations = []
    inside: dict[str, dict[str, set[str]]] = {}  # layer → part → parts it imports
    first_edge: dict[tuple[str, str], Import] = {}
    for edge in edges:
        source, target = unit_of(edge.source, rank), unit_of(edge.target, rank)
        if source is None or target is None:
            missing = edge.source if source is None else edge.target
            violations.append(Violation(edge, "?", "?", f"{missing} is in no layer"))
            continue
        (s_rank, s_name), (t_rank, t_name) = rank[source], rank[target]
        if t_rank < s_rank:
            violations.append(Violation(edge, s_name, t_name, "a lower layer imports a higher one"))
        elif t_rank == s_rank:
            a, b = (
                part_of(edge.source, source, layer_of[source]),
                part_of(edge.target, target, layer_of[target]),
            )
            # a one-folder layer's own __init__ is where its parts meet (it may gather them), not a part
            if a != b and (len(layer_of[source].units) > 1 or (a != source and b != target)):
                inside.setdefault(s_name, {}).setdefault(a, set()).add(b)
                first_edge.setdefault((a, b), edge)
    for name, graph in inside.items():
        for cycle in _cycles(graph):
            members = set(cycle)
            edge = next(e for (a, b), e in sorted(first_edge.items(), key=lambda item: item[0])
                        if a in members and b in members)  # fmt: skip
            why = "an import cycle between parts of one layer: " + " ↔ ".join(cycle)
            violations.append(Violation(edge, name, name, why))
    return violations


def loaded_by(root: Path, packages: Iterable[str], module: str) -> tuple[set[str], set[str]]:
    """What importing ``module`` runs, followed through: the tree's modules and the top names of the
    packages from outside the tree (the standard library left out)."""
    modules, edges, external = read_tree(root, tuple(packages))
    graph: dict[str, set[str]] = {}
    for edge in edges:
        graph.setdefault(edge.source, set()).add(edge.target)
    seen, todo = set(), [p for p in _with_parents(module) if p in modules]
    while todo:
        current = todo.pop()
        if current not in seen:
            seen.add(current)
            todo.extend(graph.get(current, ()))
    outside = set().union(*(external[m] for m in seen)) - set(sys.stdlib_module_names) - {"__future__"}
    return seen, outside
