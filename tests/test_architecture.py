"""One import direction over the whole graph: every module of server/, api/, sim/ and client/ imports
only its own unit or a lower layer, as docs/architecture.md writes the layers down."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from support.layers import Layer, check, loaded_by, parse_layers, read_tree

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("node_runtime", "server", "api", "sim", "client")
WEB = {"fastapi", "starlette", "uvicorn", "viser", "websockets"}


def written_layers() -> list[Layer]:
    return parse_layers((ROOT / "docs" / "architecture.md").read_text(encoding="utf-8"))


def test_architecture_every_import_follows_the_written_layers() -> None:
    violations = check(ROOT, written_layers(), PACKAGES)
    assert not violations, "\n".join(map(str, violations))


def test_architecture_the_house_has_at_most_ten_layers_of_folders() -> None:
    layers = written_layers()
    assert len(layers) <= 10, [layer.name for layer in layers]
    for layer in layers:
        for unit in layer.units:
            path = ROOT.joinpath(*unit.split("."))
            module = unit.count(".") == 1 and path.with_suffix(".py").is_file()
            # a module stands as a unit only as an entry point or as one of the runtime's parts
            entry = module and (layer.name == "entry" or unit.startswith("node_runtime."))
            assert path.is_dir() or entry or unit in {"server", "node_runtime"}, unit


def test_architecture_a_package_root_holds_only_its_entry_points_and_layer_folders() -> None:
    """server/'s root: the modules of the entry layer and the layer folders, nothing else."""
    entry = {u for layer in written_layers() for u in layer.units if layer.name == "entry"}
    for path in (ROOT / "server").glob("*.py"):
        if path.name != "__init__.py":
            assert f"server.{path.stem}" in entry, path.name


def test_architecture_every_unit_written_down_exists_once() -> None:
    units = [unit for layer in written_layers() for unit in layer.units]
    assert len(units) == len(set(units))
    for unit in units:
        path = ROOT.joinpath(*unit.split("."))
        assert path.is_dir() or path.with_suffix(".py").is_file(), unit


def test_architecture_sim_loads_only_numpy_and_the_standard_library() -> None:
    modules, outside = loaded_by(ROOT, PACKAGES, "sim")
    assert {m.split(".")[0] for m in modules} == {"sim"}
    assert outside <= {"numpy"}, outside


@pytest.mark.parametrize(
    "module", ["node_runtime.bus", "node_runtime.msgs", "node_runtime.transport", "client"]
)
def test_architecture_the_graph_below_the_web_loads_no_web_package(module: str) -> None:
    _, outside = loaded_by(ROOT, PACKAGES, module)
    assert not WEB & outside, f"importing {module} loads {sorted(WEB & outside)}"


@pytest.mark.parametrize("module", ["node_runtime.process.runner", "client.rclpy", "client.launch_ros"])
def test_architecture_a_node_process_loads_the_runtime_and_the_client_only(module: str) -> None:
    """What a student's node process runs is the runtime and client/ (one wheel), never the app."""
    loaded, _ = loaded_by(ROOT, PACKAGES, module)
    assert {m.split(".")[0] for m in loaded} <= {"node_runtime", "client"}, sorted(loaded)


def test_architecture_bus_and_messages_load_no_sim_viewer_or_api() -> None:
    for module in ("node_runtime.bus", "node_runtime.msgs"):
        loaded, _ = loaded_by(ROOT, PACKAGES, module)
        assert not {
            m
            for m in loaded
            if m.split(".")[0] in ("api", "sim") or m.startswith("server.peripherals.viewer")
        }


def test_architecture_packages_import_no_web_or_api_themselves() -> None:
    """Nodes talk to the bus, not to the web (the visualizer draws through server/peripherals/viewer)."""
    _, edges, external = read_tree(ROOT, PACKAGES)
    for module in external:
        if module.startswith("server.packages"):
            assert not {"fastapi", "viser"} & external[module], module
    assert not [
        e for e in edges if e.source.startswith("server.packages") and e.target.split(".")[0] == "api"
    ]


ROLES = frozenset({"ClassServer", "WorldWorker"})  # the classroom's two roles (server/classroom/roles.py)
ROLE_MODULES = {
    "server.classroom.class_server": {"ClassServer"},
    "server.classroom.worker_worlds": {"WorldWorker"},
}
CHECKS = frozenset({"isinstance", "issubclass", "type"})
COMPARISONS = (ast.Is, ast.IsNot, ast.Eq, ast.NotEq)


def _names(node: ast.AST) -> set[str]:
    """Every name an expression spells: ``ClassServer``, ``classroom.WorldWorker``, a tuple of them."""
    found = set()
    for sub in ast.walk(node):
        if isinstance(sub, ast.Name):
            found.add(sub.id)
        elif isinstance(sub, ast.Attribute):
            found.add(sub.attr)
    return found


def _named(node: ast.AST) -> set[str]:
    """The names a type check, a type comparison, a ``match`` class pattern or an import spells."""
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in CHECKS:
        return _names(node)
    if isinstance(node, ast.Compare) and any(isinstance(op, COMPARISONS) for op in node.ops):
        return _names(node)
    if isinstance(node, ast.MatchClass):
        return _names(node.cls)
    if isinstance(node, ast.ImportFrom):
        return {alias.name for alias in node.names} | ROLE_MODULES.get(node.module or "", set())
    if isinstance(node, ast.Import):
        return set().union(*(ROLE_MODULES.get(alias.name, set()) for alias in node.names))
    return set()


def role_checks(source: str) -> list[str]:
    """Where ``source`` asks which classroom role it has: ``isinstance``/``issubclass``/``type(...)``
    naming a role, a comparison with one, a ``match`` pattern of one, or an import of one."""
    return [
        f"line {getattr(node, 'lineno', '?')}: {ast.unparse(node)[:100]}"
        for node in ast.walk(ast.parse(source))
        if _named(node) & ROLES
    ]


def test_architecture_the_api_never_asks_which_classroom_role_it_serves() -> None:
    """api/ calls the classroom through its Protocol alone (``Classroom``): no isinstance, issubclass,
    type() or match on ClassServer or WorldWorker, nor an import of either; where the roles differ,
    the role's own method answers."""
    found = {
        str(path.relative_to(ROOT)): checks
        for path in sorted((ROOT / "api").rglob("*.py"))
        if (checks := role_checks(path.read_text(encoding="utf-8")))
    }
    assert not found, found


@pytest.mark.parametrize(
    "source",
    [
        "if isinstance(classroom, ClassServer): pass",
        "ok = not isinstance(c, (Lab, classroom.WorldWorker))",
        "ok = issubclass(kind, ClassServer)",
        "ok = type(classroom) is WorldWorker",
        "ok = type(classroom).__name__ == 'x' or type(classroom) == ClassServer",
        "match classroom:\n    case WorldWorker(): pass",
        "from server.classroom import Classroom, ClassServer",
        "from server.classroom.worker_worlds import socket_here",
        "import server.classroom.class_server",
    ],
)
def test_checker_sees_every_way_of_asking_for_a_role(source: str) -> None:
    assert role_checks(source), source


def test_checker_lets_the_protocol_and_other_checks_be() -> None:
    source = (
        "from server.classroom import Classroom, ClassroomError\n"
        "def f(classroom: Classroom, exc: Exception) -> bool:\n"
        "    return isinstance(exc, ClassroomError) and classroom.workers is None\n"
    )
    assert role_checks(source) == []


# The checker itself, on small trees written here: it must see what it is there to see.

FAKE_LAYERS = """# A house
```layers
web: top.web
logic: top.logic top.store
base: top.base
namespace: top
```
"""


def write_tree(root: Path, files: dict[str, str]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


CLEAN = {
    "top/__init__.py": "",
    "top/web/__init__.py": "from top.logic import run\n",
    "top/web/routes.py": "from ..logic import run\nfrom . import helpers\n",
    "top/web/helpers.py": "import fastapi\n",
    "top/logic/__init__.py": "from .core import run\n",
    "top/logic/core.py": "from top.base.values import Value\n\ndef run() -> None:\n    import top.base\n",
    "top/store/__init__.py": "import top.base.values\n",
    "top/base/__init__.py": "",
    "top/base/values.py": "import json\nimport numpy\nValue = int\n",
}


def fake_check(root: Path, files: dict[str, str]) -> list[str]:
    write_tree(root, files)
    return [str(v) for v in check(root, parse_layers(FAKE_LAYERS), ["top"])]


def test_checker_clean_tree_reports_nothing(tmp_path: Path) -> None:
    assert fake_check(tmp_path, CLEAN) == []


def test_checker_lower_layer_importing_a_higher_one_is_reported(tmp_path: Path) -> None:
    found = fake_check(tmp_path, {**CLEAN, "top/base/values.py": "from top.web.routes import x\n"})
    assert len(found) == 2  # the package top.web runs too
    assert all("top.base.values (base) imports top.web" in f for f in found)
    assert "lower layer imports a higher one" in found[0]
    assert str(tmp_path / "top/base/values.py") + ":1" in found[0]


@pytest.mark.parametrize(
    ("source", "where"),
    [
        ("def later() -> None:\n    from top.logic import core\n", "inside a function"),
        (
            "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from top.logic.core import run\n",
            "TYPE_CHECKING",
        ),
        ("from ...logic import core\n", "relative"),
        ("from ..logic import core\n", "relative, to a package"),
        ("import top.logic.core as c\n", "import ... as"),
        ("from top import logic\n", "a subpackage named in from-import"),
    ],
)
def test_checker_every_kind_of_import_is_seen(tmp_path: Path, source: str, where: str) -> None:
    files = {**CLEAN, "top/base/deep/__init__.py": "", "top/base/deep/mod.py": source}
    if where == "relative, to a package":
        files["top/base/mod.py"] = files.pop("top/base/deep/mod.py")
    found = fake_check(tmp_path, files)
    assert found, where
    assert all("(base) imports top.logic" in f for f in found), found


def test_checker_a_package_that_runs_a_higher_layer_is_reported_for_its_importers(tmp_path: Path) -> None:
    """``import top.base.values`` runs ``top/base/__init__.py`` first: what that imports counts."""
    found = fake_check(tmp_path, {**CLEAN, "top/base/__init__.py": "from top import web\n"})
    assert found == [
        f"{tmp_path / 'top/base/__init__.py'}:1: top.base (base) imports top.web (web): "
        "a lower layer imports a higher one"
    ]


def test_checker_peers_of_one_layer_may_import_one_another_one_way(tmp_path: Path) -> None:
    assert fake_check(tmp_path, {**CLEAN, "top/store/__init__.py": "from top.logic import run\n"}) == []


def test_checker_an_import_cycle_between_peers_of_one_layer_is_reported(tmp_path: Path) -> None:
    found = fake_check(
        tmp_path,
        {
            **CLEAN,
            "top/store/__init__.py": "from top.logic import run\n",
            "top/logic/core.py": "import top.store\n\ndef run() -> None: ...\n",
        },
    )
    assert len(found) == 1
    assert "an import cycle between parts of one layer: top.logic ↔ top.store" in found[0]


def test_checker_the_parts_of_a_one_folder_layer_may_not_import_in_a_circle(tmp_path: Path) -> None:
    """A layer that is one folder (web) has parts one level down: routes may use helpers, but a
    helper that imports routes back closes a circle, even under TYPE_CHECKING."""
    helpers = "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from top.web.routes import x\n"
    found = fake_check(tmp_path, {**CLEAN, "top/web/helpers.py": helpers})
    assert len(found) == 1
    assert "top.web.helpers ↔ top.web.routes" in found[0]


def test_checker_a_module_in_no_layer_is_reported(tmp_path: Path) -> None:
    files = {**CLEAN, "other/__init__.py": "", "top/logic/core.py": "import other\n"}
    write_tree(tmp_path, files)
    found = [str(v) for v in check(tmp_path, parse_layers(FAKE_LAYERS), ["top", "other"])]
    assert any("other is in no layer" in f for f in found)


def test_checker_a_new_module_beside_the_units_of_a_package_is_in_no_layer(tmp_path: Path) -> None:
    """``top`` holds only its ``__init__``: a module added beside ``top.web`` must be placed."""
    found = fake_check(tmp_path, {**CLEAN, "top/extra.py": "from top.base import values\n"})
    assert found and all("top.extra is in no layer" in f for f in found)


def test_checker_loaded_by_follows_imports_through(tmp_path: Path) -> None:
    write_tree(tmp_path, CLEAN)
    modules, outside = loaded_by(tmp_path, ["top"], "top.web.routes")
    assert {"top", "top.web", "top.web.helpers", "top.logic.core", "top.base.values"} <= modules
    assert outside == {"fastapi", "numpy"}  # json is the standard library's
    modules, outside = loaded_by(tmp_path, ["top"], "top.store")
    assert "top.web" not in modules and outside == {"numpy"}


def test_checker_needs_the_layers_block() -> None:
    with pytest.raises(ValueError, match="no ```layers block"):
        parse_layers("# no block here\n")
