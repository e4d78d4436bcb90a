"""The classroom's errors: a refused request, with the HTTP status that says why; and students'
nodes refused on a world worker that cannot reach the class's router from a sandbox."""

from __future__ import annotations

from server.host.processes.sandbox import StudentCodeRefusedError


class ClassroomError(Exception):
    """A refused classroom request: ``status`` is the HTTP status that says why; a refusal that
    passes with time (a rate limit) says when to try again in ``retry_after_s``."""

    def __init__(self, status: int, message: str, retry_after_s: float | None = None) -> None:
        super().__init__(message)
        self.status = status
        self.retry_after_s = retry_after_s


class StudentCodeElsewhereError(StudentCodeRefusedError):
    """A world worker with no way for a sandboxed node to reach the class's router: not on the class
    server's machine, and joined to the router over something other than plain TCP, which its relay
    cannot carry (node_runtime/transport/socket_relay.py). None of its worlds' students' nodes start."""

    def __init__(self, world: str) -> None:
        RuntimeError.__init__(
            self,
            f"students' nodes do not run in world {world!r}: it runs on a world worker on another machine "
            "than the class server, joined to the class's router other than by plain tcp/, and a student's "
            "sandboxed node reaches the router only through a Unix socket there or the worker's relay to tcp/",
        )
