"""The error responses a route can give, for the OpenAPI document (api/errors.py produces them)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, Field


class ErrorBody(BaseModel):
    """Every error the app answers: ``detail`` names the problem (FastAPI's validation errors give a
    list of ``{type, loc, msg}``); a 500 adds the ``request_id`` its log entry carries."""

    detail: str | list[dict[str, Any]] = Field(examples=["unknown topic '/nope'"])
    request_id: str | None = Field(default=None, description="only on a 500: find it in the server log")


class StaleSave(BaseModel):
    """A save over a version that is not the file's now (412): what happened, and the file's version
    now, so the page can offer the choice."""

    detail: str
    etag: str | None = Field(description="the file's version now; null: it is gone")


UNAUTHORIZED = 401
FORBIDDEN = 403
NOT_FOUND = 404
TYPE_CONFLICT = 409
PRECONDITION = 412
UNPROCESSABLE = 422
TOO_MANY = 429
NO_ANSWER = 504
BAD_GATEWAY = 502
NO_ROOM = 503
_DESCRIPTIONS = {
    400: "the request is malformed: a path a normaliser would change (./, ../, //, a backslash, "
    "%2e, %2f, %5c), or what the detail names",
    401: "no valid token (a class server, or a lab started with --token): the lab_token cookie or "
    "Authorization: Bearer",
    403: "refused: another site's page may not write (Origin), or the token does not reach this "
    "(the wrong class code, another student's world, the instructor's controls)",
    404: "no such topic, node, service, type, package, publisher, launch, bag, playback, world or "
    "workspace file, or no Zenoh graph",
    409: "the topic carries another type, the thing was destroyed, the bag exists or is still "
    "recording, or the name or path is taken",
    412: "the file changed since it was read (If-Match), or exists (If-None-Match: *): `etag` is its "
    "version now",
    413: "the body is larger than the limit (64 KiB; a checkpoint's capture 2 MiB, a report to verify "
    "8 MiB, a workspace route's 8 MiB), an answer over 8 KiB, or a file, the workspace or an upload "
    "over its limit",
    415: "a file that is not UTF-8 text (a binary file, a NUL character)",
    421: "the Host header is not a name of this server",
    422: "a field, a number, a name or a workspace path is invalid, or an upload is not a zip the "
    "workspace takes (the detail names it)",
    429: "a limit is reached (publishers, launches, topics, recordings, playbacks, worlds in a class, "
    "a world's writes per second)",
    500: "a bug: the detail carries a request id, the log has the traceback",
    502: "a world worker did not answer",
    503: "no place in the class has room for another world, or the world is moving to another worker",
    504: "the service did not answer in time (its server is gone, busy or crashed)",
}
_ALWAYS = (400, 421, 500)  # any route: the path check, the Host guard, and a bug
_WRITES = (400, 403, 413, 422)  # any route with a JSON body: the Origin guard, size, strict JSON


def responses(*codes: int, body: bool = False) -> dict[int | str, dict[str, Any]]:
    """OpenAPI ``responses`` for these statuses, plus those every route (and every write) can give."""
    chosen = {*codes, *_ALWAYS, *(_WRITES if body else ())}
    return {
        code: {"model": StaleSave if code == PRECONDITION else ErrorBody, "description": _DESCRIPTIONS[code]}
        for code in sorted(chosen)
    }
