"""The classroom's errors: a refused request, with the HTTP status that says why; and students'
nodes refused on a world worker that cannot reach the class's router from a sandbox."""

from __future__ import annotations

from server.processes.sandbox import StudentCodeRefusedError


class ClassroomError(Exception):
    """A refused classroom request: ``status`` is the HTTP status that says why; a refusal that
    passes with time (a rate limit) says when to try again in ``retry_after_s``."""

    def __init__(self, status: int, message: str, retry_after_s: float | None = None) -> None:
        super().__init__(message)
        self.status = status
        self.retry_after_s = retry_after_s


class StudentCodeElsewhereError(StudentCodeRefusedError):
    """A world worker without the class router's Unix socket (it runs on another machine than the
    class server): its worlds' sandboxed nodes could not reach their graph, so none start."""

    def __init__(self, world: str) -> None:
        RuntimeError.__init__(
            self,
            f"students' nodes do not run in world {world!r}: it runs on a world worker on another machine "
            "than the class server, and a student's node reaches the class's router only through its "
            "Unix socket there",
        )
