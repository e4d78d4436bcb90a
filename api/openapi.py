"""The OpenAPI document of an app behind tokens (a class server, or one lab with ``--token``).

FastAPI writes the routes' document; this adds how a caller shows its token (a bearer token or
the page's HTTP-only cookie), requires one on every operation but those that say
``openapi_extra={"security": []}``, and lists the 401 such an operation answers without it. On a
class server a lab's operation also takes the instructor's ``X-Lab-World`` header, and may answer
400 (the instructor named no world), 403 (another student's world), 404 (no such world), 502 or
503 (the world's worker did not answer, or the world is moving) and, for a write, 429 (the
world's writes per second).
"""

from __future__ import annotations

from typing import Any

from fastapi import FastAPI

from api.deps import SAFE_METHODS, TOKEN_COOKIE
from api.protocol.responses import (
    BAD_GATEWAY,
    FORBIDDEN,
    NO_ROOM,
    NOT_FOUND,
    TOO_MANY,
    UNAUTHORIZED,
    responses,
)

SCHEMES = {
    "bearer": {
        "type": "http",
        "scheme": "bearer",
        "description": "the token the server printed or a join gave",
    },
    "cookie": {
        "type": "apiKey",
        "in": "cookie",
        "name": TOKEN_COOKIE,
        "description": "the page's HTTP-only cookie",
    },
}
_METHODS = ("get", "put", "post", "delete", "patch", "head", "options")
WORLD_HEADER = {
    "name": "X-Lab-World",
    "in": "header",
    "required": False,
    "schema": {"type": "string", "maxLength": 32},
    "description": "the instructor's: the world this call acts on (a student's token names its own)",
}
_ERROR_CONTENT = {"application/json": {"schema": {"$ref": "#/components/schemas/ErrorBody"}}}


def _add_response(operation: dict[str, Any], code: int) -> None:
    description = responses(code)[code]["description"]
    operation.setdefault("responses", {}).setdefault(
        str(code), {"description": description, "content": _ERROR_CONTENT}
    )


def add_token_security(schema: dict[str, Any], *, classroom: bool = False) -> dict[str, Any]:
    """``schema`` with the token schemes, required everywhere not marked open, and their 401; on a
    class server (``classroom``) the world header and refusals of a world's operations too."""
    components = schema.setdefault("components", {})
    components.setdefault("securitySchemes", {}).update(SCHEMES)
    schema["security"] = [{"bearer": []}, {"cookie": []}]
    for path, operations in schema.get("paths", {}).items():
        for method, operation in operations.items():
            if method not in _METHODS or operation.get("security") == []:
                continue
            _add_response(operation, UNAUTHORIZED)
            if not classroom or path.startswith("/api/classroom/"):
                continue
            operation.setdefault("parameters", []).append(dict(WORLD_HEADER))
            codes = (400, FORBIDDEN, NOT_FOUND, BAD_GATEWAY, NO_ROOM)
            for code in codes if method.upper() in SAFE_METHODS else (*codes, TOO_MANY):
                _add_response(operation, code)
    return schema


def use_token_security(app: FastAPI, *, classroom: bool) -> None:
    """Make ``app.openapi()`` (and /openapi.json) document the token: FastAPI's own document, built
    and cached as always, amended once."""
    plain = app.openapi

    def openapi() -> dict[str, Any]:
        if app.openapi_schema is None:
            add_token_security(plain(), classroom=classroom)  # plain() caches it as app.openapi_schema
        return app.openapi_schema  # type: ignore[return-value]

    app.openapi = openapi  # type: ignore[method-assign]
