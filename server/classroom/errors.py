"""The classroom's one error: a refused request, with the HTTP status that says why."""

from __future__ import annotations


class ClassroomError(Exception):
    """A refused classroom request: ``status`` is the HTTP status that says why; a refusal that
    passes with time (a rate limit) says when to try again in ``retry_after_s``."""

    def __init__(self, status: int, message: str, retry_after_s: float | None = None) -> None:
        super().__init__(message)
        self.status = status
        self.retry_after_s = retry_after_s
