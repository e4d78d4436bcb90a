"""sim/ stays pure: numpy and the standard library only, no clock, no I/O, no global randomness."""

from __future__ import annotations

import ast
from pathlib import Path

SIM_ROOT = Path(__file__).resolve().parents[2] / "sim"
ALLOWED = {"__future__", "collections", "dataclasses", "math", "typing", "numpy", "sim"}


def _imported_roots(path: Path) -> set[str]:
    roots = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            roots |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            roots.add(node.module.split(".")[0])
    return roots


def test_sim_modules_import_only_numpy_and_pure_stdlib() -> None:
    files = sorted(SIM_ROOT.rglob("*.py"))
    assert files
    offenders = {str(f.relative_to(SIM_ROOT)): _imported_roots(f) - ALLOWED for f in files}
    assert {name: bad for name, bad in offenders.items() if bad} == {}


def test_sim_modules_use_no_global_numpy_random() -> None:
    for path in SIM_ROOT.rglob("*.py"):
        assert "np.random." not in path.read_text().replace("np.random.Generator", ""), path
