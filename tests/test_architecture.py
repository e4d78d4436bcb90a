"""One dependency direction: sim/ knows nothing of the server; the bus knows nothing of the web."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def imported_roots(folder: Path) -> dict[str, set[str]]:
    found: dict[str, set[str]] = {}
    for path in folder.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            else:
                continue
            for name in names:
                found.setdefault(name.split(".")[0], set()).add(str(path.relative_to(ROOT)))
    return found


def test_sim_imports_no_server_api_or_web_packages() -> None:
    roots = imported_roots(ROOT / "sim")
    assert not {"server", "api", "fastapi", "starlette", "viser", "uvicorn", "websockets"} & set(roots)


def test_bus_and_messages_import_no_web_sim_or_viewer() -> None:
    for folder in ("server/bus", "server/msgs"):
        roots = imported_roots(ROOT / folder)
        assert not {"api", "fastapi", "starlette", "viser", "uvicorn", "sim"} & set(roots), folder


def test_api_is_the_only_layer_using_fastapi_routes() -> None:
    roots = imported_roots(ROOT / "server" / "packages")
    assert not {"fastapi", "api", "viser"} & set(roots), "nodes talk to the bus, not to the web"
