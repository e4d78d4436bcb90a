"""Every HTTP route of the real app says what it answers: a shape declared in api/protocol/ (a
pydantic model, a TypedDict, a list or union of them), or a Response class of its own for what is
not JSON (a file, a zip, a page, CSV). Its handler returns that shape, never a bare dict, so the
type checker holds the handler to the shape the OpenAPI document and the page's types show."""

from __future__ import annotations

import types
import typing
from typing import Any

import pytest
from fastapi import FastAPI
from fastapi.datastructures import DefaultPlaceholder
from fastapi.routing import APIRoute, iter_route_contexts
from pydantic import BaseModel
from starlette.responses import Response
from typing_extensions import is_typeddict

from server.app import create_app
from server.host.settings import ClassroomSettings, Settings

SCALARS = (str, int, float, bool)


class Shape(BaseModel):
    x: int


def _declared(kind: Any, *, responses: bool) -> bool:
    """Whether ``kind`` is a declared shape (or, with ``responses``, a Response class too)."""
    origin = typing.get_origin(kind)
    if origin is typing.Annotated:
        return _declared(typing.get_args(kind)[0], responses=responses)
    if origin in (typing.Union, types.UnionType):
        members = [m for m in typing.get_args(kind) if m is not type(None)]
        return bool(members) and all(_declared(m, responses=responses) for m in members)
    if origin is list:
        (item,) = typing.get_args(kind)
        return item in SCALARS or _declared(item, responses=False)
    if not isinstance(kind, type):
        return False  # Any, a bare dict alias, None
    if responses and issubclass(kind, Response):
        return True
    return (issubclass(kind, BaseModel) and kind is not BaseModel) or is_typeddict(kind)


def _routes(app: FastAPI) -> list[tuple[str, APIRoute]]:
    found = []
    for context in iter_route_contexts(app.routes):
        route = context.original_route
        if isinstance(route, APIRoute):
            found.append((f"{','.join(sorted(route.methods))} {context.path}", route))
    return found


def undeclared(app: FastAPI) -> list[str]:
    """Each route whose answer is not declared, and why."""
    problems = []
    for name, route in _routes(app):
        own_class = not isinstance(route.response_class, DefaultPlaceholder)
        if not own_class and not _declared(route.response_model, responses=False):
            problems.append(f"{name}: response model {route.response_model!r} is no declared shape")
        returns = typing.get_type_hints(route.endpoint, include_extras=True).get("return")
        if not _declared(returns, responses=True):
            problems.append(f"{name}: {route.endpoint.__qualname__} returns {returns!r}")
    return problems


@pytest.fixture(scope="module")
def apps() -> dict[str, FastAPI]:
    """The app a lab serves and the one a class server serves, built but not started."""
    return {
        "lab": create_app(Settings()),
        "class server": create_app(Settings(classroom=ClassroomSettings(code="K7PX2M"))),
    }


@pytest.mark.parametrize("which", ["lab", "class server"])
def test_every_route_declares_its_answer(apps: dict[str, FastAPI], which: str) -> None:
    app = apps[which]
    assert len(_routes(app)) > 60, "the app's routes were not all found"

    assert undeclared(app) == []


def test_the_check_sees_a_bare_dict_and_a_missing_model() -> None:
    app = FastAPI()

    @app.get("/bare")
    async def bare() -> dict[str, Any]:
        return {}

    @app.get("/none", response_model=None)
    async def none() -> Any:
        return {}

    @app.get("/file", response_class=Response)
    async def file() -> Response:
        return Response(b"")

    @app.get("/shape")
    async def shape() -> Shape:
        return Shape(x=1)

    problems = undeclared(app)

    assert [p.split(":")[0] for p in problems] == ["GET /bare", "GET /bare", "GET /none", "GET /none"]
