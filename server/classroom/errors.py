"""The classroom's one error: a refused request, with the HTTP status that says why."""

from __future__ import annotations


class ClassroomError(Exception):
    """A refused classroom request: ``status`` is the HTTP status that says why."""

    def __init__(self, status: int, message: str) -> None:
        super().__init__(message)
        self.status = status
