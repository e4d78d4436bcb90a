"""Asking the lab how to join its ROS graph (``GET /api/zenoh/join``), as ``ros2lab run`` and
``ros2lab env`` do, with a bounded wait.

A lab that does not answer (nothing listens, or it accepts and never replies, or it answers 5xx)
is asked again with a growing pause, for at most ``wait_s`` seconds in all (one request may take
all that is left: a saturated lab answers slowly, and that answer is good); then one line says
so and the command ends non-zero. Nothing falls back to another router or domain: a node started
anyway would join a graph nobody watches. A lab that answers "not yet" (429: too many node
processes starting at once on it, see server/host/processes/start_pacing.py) is asked again at
the time it gives (``Retry-After-Ms``, else ``Retry-After``) with the ticket it gave
(``Start-Turn``; the first ask says ``turn=new``), which keeps this start's turn for it, for at
most ``queue_s`` seconds; that wait is the lab's own pacing and does not count as not
answering. Any other error (no Zenoh graph, a bad token) ends at once.
"""

from __future__ import annotations

import random
import sys
import time
from collections.abc import Callable
from typing import Any

from server.cli.errors import ApiError, CliError, NoServerError
from server.cli.plain_get import LabGetter

JOIN_PATH = "/api/zenoh/join"
WAIT_S = 20.0  # for a lab that does not answer
QUEUE_S = 300.0  # for a lab that answers "not yet"
FIRST_PAUSE_S = 0.25
MAX_PAUSE_S = 4.0
NOTE_AFTER_S = 5.0  # a wait this long is said once on stderr
TOO_MANY = 429
RETRIED_STATUSES = (502, 503, 504)
JITTER_S = 0.25  # at most this much added to a "not yet"'s wait: spreads a class's retries
TURN_CHARS = 64  # a turn's ticket is shorter (the lab refuses a longer one)
NEW_TURN = "new"  # asked with first: this start comes back with the ticket it is given


class JoinError(CliError):
    """The lab did not tell how to join its graph within the bounded wait."""


def _say(line: str) -> None:
    print(line, file=sys.stderr, flush=True)


class Pacing:
    """The waits of one join; ``clock``, ``sleep`` and ``jitter`` (0..1, spreads a class's retries)
    are injected for tests. A plain class: ``dataclasses`` imports ``inspect``, a tenth of the
    CPU ``ros2lab run`` spends before it asks for its turn (server/cli/plain_get.py)."""

    def __init__(
        self,
        wait_s: float = WAIT_S,
        queue_s: float = QUEUE_S,
        clock: Callable[[], float] = time.monotonic,
        sleep: Callable[[float], None] = time.sleep,
        jitter: Callable[[], float] = random.random,
        say: Callable[[str], None] = _say,
    ) -> None:
        self.wait_s, self.queue_s = wait_s, queue_s
        self.clock, self.sleep, self.jitter, self.say = clock, sleep, jitter, say


def join_graph(
    client: LabGetter,
    pacing: Pacing | None = None,
    *,
    start: bool = False,
    meanwhile: Callable[[], object] | None = None,
) -> dict[str, Any]:
    """The lab's answer to ``GET /api/zenoh/join``, asked until it gives one (see the module);
    ``start``: a node process starts once it has the answer (the lab paces those). ``meanwhile``
    is called once, at the first "not yet", before waiting for the turn (what it takes comes off
    the wait; what it raises ends the join): ``ros2lab run`` finds its file then."""
    pacing = pacing or Pacing()
    started = pacing.clock()
    unanswered_since: float | None = None
    pause = FIRST_PAUSE_S
    noted = False
    turn = NEW_TURN  # then the ticket of the turn the lab keeps for this start
    while True:
        attempted = pacing.clock()
        bound = pacing.wait_s - (attempted - unanswered_since if unanswered_since is not None else 0.0)
        params = {"start": "true", "turn": turn} if start else None
        try:
            timeout_s = max(0.1, bound)  # a slow answer (a saturated lab) is an answer: wait for it
            answer: dict[str, Any] = client.get(JOIN_PATH, params, timeout_s)
            return answer
        except ApiError as exc:
            if exc.status == TOO_MANY and exc.retry_after_s is not None:
                unanswered_since, pause = None, FIRST_PAUSE_S
                turn = exc.turn if exc.turn and len(exc.turn) <= TURN_CHARS else NEW_TURN
                # A kept turn is this start's alone: back at it, not spread like a new start.
                spread = 0.0 if turn != NEW_TURN else pacing.jitter() * min(exc.retry_after_s, JITTER_S)
                delay = exc.retry_after_s + spread
                if pacing.clock() + delay - started > pacing.queue_s:
                    raise JoinError(
                        f"the lab at {client.base_url} was still pacing node starts after "
                        f"{pacing.queue_s:.0f} s ({exc.detail}); try again later"
                    ) from None
                if meanwhile is not None:
                    before = pacing.clock()
                    meanwhile()
                    delay -= pacing.clock() - before
                    meanwhile = None
                if not noted and pacing.clock() + delay - started >= NOTE_AFTER_S:
                    pacing.say("ros2lab: the lab is starting other nodes first; waiting for its turn ...")
                    noted = True
                pacing.sleep(max(0.0, delay))
                continue
            if exc.status not in RETRIED_STATUSES:
                raise
            problem = f"HTTP {exc.status}"
        except NoServerError:
            problem = "connection refused"
        except CliError as exc:  # a timeout or a connection dropped without an answer
            problem = str(exc)
        if unanswered_since is None:
            unanswered_since = attempted
        if pacing.clock() - unanswered_since + pause > pacing.wait_s:
            raise JoinError(
                f"the lab at {client.base_url} did not tell how to join its graph within "
                f"{pacing.wait_s:.0f} s ({problem}); the node was not started"
            ) from None
        pacing.sleep(pause)
        pause = min(MAX_PAUSE_S, pause * 2)
