"""The real app behind a TestClient, its FastAPI object reused between tests of equal settings.

Building the app (its routes and their pydantic models) costs about half a second of CPU, and
hundreds of API tests each start one with the same few settings. Everything a test can change
lives in the lab, which the app's lifespan makes new each time a TestClient enters it and stops
when it leaves; the FastAPI object itself keeps only its settings and routes. So an app is handed
to one TestClient at a time and, once that one has left, to the next test asking for equal
settings. A class server is never reused: its Classroom lives outside the lifespan.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from fastapi import FastAPI
from fastapi.testclient import TestClient

from server.app import create_app
from server.host.settings import Settings

_idle: dict[str, list[FastAPI]] = {}  # by repr(settings): Settings holds a dict, so is unhashable


@contextmanager
def lab_client(settings: Settings) -> Iterator[TestClient]:
    """A TestClient on an app for ``settings``, its lifespan (a new lab) entered."""
    if settings.classroom is not None:
        with TestClient(create_app(settings)) as client:
            yield client
        return
    idle = _idle.setdefault(repr(settings), [])
    app = idle.pop() if idle else create_app(settings)
    try:
        with TestClient(app) as client:
            yield client
    finally:
        idle.append(app)
