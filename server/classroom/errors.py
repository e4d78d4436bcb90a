"""The classroom's refusals, one class for each reason, and students' nodes refused on a world worker
that cannot reach the class's router from a sandbox.

A refusal names why, never how a protocol answers it: api/errors.py gives each its HTTP status
and WebSocket close code, in its one table. Catch ``ClassroomError`` for any of them.
"""

from __future__ import annotations

from server.host.processes.sandbox import StudentCodeRefusedError


class ClassroomError(Exception):
    """A refused classroom request; a refusal that passes with time (a rate limit, a full class)
    says when to try again in ``retry_after_s`` (None: it does not say)."""

    retry_after_s: float | None = None

    def __init__(self, message: str, retry_after_s: float | None = None) -> None:
        super().__init__(message)
        self.retry_after_s = retry_after_s


# -- who is calling ----------------------------------------------------------------------------
class NotAuthenticatedError(ClassroomError):
    """No valid token: not joined yet, a token this server did not sign or has revoked, or a lab
    behind ``--token`` called without it."""


class WorldNotNamedError(ClassroomError):
    """The instructor's call names no world (the X-Lab-World header or ``?world=``)."""


class NotYoursError(ClassroomError):
    """A student's token used on another student's world."""


class WrongCodeError(ClassroomError):
    """A join with another class's code."""


# -- where it is asked -------------------------------------------------------------------------
class JoinThroughClassServerError(ClassroomError):
    """A join sent to a world worker: students join through its class server."""


class NotHereError(ClassroomError):
    """What this role does not do or keep: a world worker has no load or queue of the class, and
    keeps no record of whose progress is whose; a class server hosts no world for another."""


class WorldElsewhereError(ClassroomError):
    """A world that runs on a world worker, asked of this process, which has nothing of it."""


# -- which world -------------------------------------------------------------------------------
class UnknownWorldError(ClassroomError):
    """No world of that name."""


class NameTakenError(ClassroomError):
    """A world of that name is in the class already, starting, or waiting to join."""


class BadNameError(ClassroomError):
    """A student's name that makes no world name, or holds a character no name may hold."""


# -- the class's room and its limits -----------------------------------------------------------
class ClassFullError(ClassroomError):
    """The class (or a world worker) holds as many worlds as it may, or every ROS domain is taken."""


class AddressLimitError(ClassroomError):
    """One client address holds as many worlds of the class as it may."""


class RateLimitedError(ClassroomError):
    """Too many joins, wrong codes, writes or resets in a short while; ``retry_after_s`` says when."""


class AtCapacityError(ClassroomError):
    """The class server is at its capacity and no join may wait (no queue, or the queue is full);
    ``retry_after_s`` says when to try again."""


class JoinLapsedError(ClassroomError):
    """A waiting join that left the queue: it was not polled in time, or waited too long."""


class UnknownTicketError(ClassroomError):
    """No join waits with this ticket."""


class NoRoomError(ClassroomError):
    """No place has room for another world: the class server's own and every world worker's are full."""


# -- a student's saved progress ----------------------------------------------------------------
class ProgressOwnedError(ClassroomError):
    """A join under a name whose saved progress or code is another student's (or whose owner record
    cannot be read)."""


class WorldJoinedError(ClassroomError):
    """The progress of a world joined now is its student's: it is not released."""


class NoSavedProgressError(ClassroomError):
    """No saved progress with an owner under that name."""


class BadHandoverError(ClassroomError):
    """A world's progress handed to a world worker that is not a progress."""


# -- the class server's world workers ----------------------------------------------------------
class WorkerFailedError(ClassroomError):
    """A world worker that did not answer, answered what is not an answer, or did not take a world's
    files (or a world's files that could not be read to hand over)."""


class WorkerTimeoutError(ClassroomError):
    """A world worker that did not answer in time."""


class WorkerRefusedError(ClassroomError):
    """A world worker that refused a call: ``answered`` is the status of its own reply, which the
    class server passes on when it is the caller's fault (a client error), and a server error of
    the worker's otherwise (None: not known)."""

    answered: int | None = None

    def __init__(self, message: str, answered: int) -> None:
        super().__init__(message)
        self.answered = answered


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
