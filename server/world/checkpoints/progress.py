"""One world's checkpoints as they stand: what was met (the first time, the newest evidence), the
answers, the page's captures. It outlives the world's lab: a reset starts the checks over, not this;
store.py keeps it on disk across restarts of the server."""

from __future__ import annotations

import secrets
import time
from collections.abc import Callable
from dataclasses import dataclass
from datetime import UTC, datetime

from server.world.checkpoints.declared import Checkpoint, Evidence, Question

MAX_ANSWER_BYTES = 8 * 1024
MAX_CAPTURE_BYTES = 2 * 1024 * 1024
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def iso(epoch_s: float | None) -> str | None:
    """``epoch_s`` as ISO 8601 UTC (what the API and the report show)."""
    if epoch_s is None:
        return None
    return datetime.fromtimestamp(epoch_s, UTC).isoformat(timespec="seconds").replace("+00:00", "Z")


class UnknownQuestionError(LookupError):
    def __init__(self, qid: str, known: list[str]) -> None:
        super().__init__(f"no question {qid!r} (questions: {', '.join(known)})")


class UnknownCheckpointError(LookupError):
    def __init__(self, name: str, known: list[str]) -> None:
        super().__init__(f"no checkpoint {name!r} (checkpoints: {', '.join(known)})")


class TooLargeError(ValueError):
    pass


class NotPngError(ValueError):
    pass


@dataclass
class Record:
    done_at_s: float  # wall clock, s since the epoch (the first time it was met: it never moves)
    evidence: Evidence
    times: int = 1


@dataclass
class Answer:
    text: str = ""
    saved_at_s: float | None = None


class Progress:
    def __init__(
        self,
        checkpoints: tuple[Checkpoint, ...],
        student: str | None = None,
        wall: Callable[[], float] = time.time,
    ) -> None:
        self.checkpoints = checkpoints
        self.student = student
        self.wall = wall
        self.records: dict[str, Record] = {}
        self.answers: dict[str, Answer] = {q.id: Answer() for c in checkpoints for q in c.questions}
        self.captures: dict[str, bytes] = {}  # PNG bytes, by checkpoint
        self.version = 0
        # Tells this Progress from another of the same world (handover.py's tag, with ``version``).
        self.instance = secrets.token_hex(8)
        # Called after every change (store.py's: queues a copy to write; never blocks).
        self.on_change: Callable[[], None] | None = None

    @property
    def questions(self) -> list[tuple[Checkpoint, Question]]:
        return [(c, q) for c in self.checkpoints for q in c.questions]

    def checkpoint(self, name: str) -> Checkpoint:
        for c in self.checkpoints:
            if c.name == name:
                return c
        raise UnknownCheckpointError(name, [c.name for c in self.checkpoints])

    def met(self, name: str, evidence: Evidence) -> Record:
        """Checkpoint ``name`` was met (again): keep it done, with this newest evidence. Its done
        time stays the first: the student's Guide and the instructor's table read it at different
        moments, and a time that moved with every repeat showed them two."""
        old = self.records.get(name)
        if old is None:
            record = Record(self.wall(), evidence)
        else:
            record = Record(old.done_at_s, evidence, old.times + 1)
        self.records[name] = record
        self._changed()
        return record

    def answer(self, qid: str, text: str) -> Answer:
        if qid not in self.answers:
            raise UnknownQuestionError(qid, list(self.answers))
        size = len(text.encode())
        if size > MAX_ANSWER_BYTES:
            raise TooLargeError(f"an answer is at most {MAX_ANSWER_BYTES} bytes of UTF-8; this one is {size}")
        answer = self.answers[qid] = Answer(text, self.wall())
        self._changed()
        return answer

    def capture(self, name: str, png: bytes) -> None:
        self.checkpoint(name)
        if len(png) > MAX_CAPTURE_BYTES:
            raise TooLargeError(f"a capture is at most {MAX_CAPTURE_BYTES} bytes; this one is {len(png)}")
        if not png.startswith(PNG_MAGIC):
            raise NotPngError("a capture must be a PNG image (it does not start with PNG's signature)")
        self.captures[name] = png
        self._changed()

    def _changed(self) -> None:
        self.version += 1
        if self.on_change is not None:
            self.on_change()
