"""One world's progress as its file keeps it: what was met (its first time, newest evidence and count)
and the answers, as JSON; the captures are PNG files beside it (store.py). Reading takes only what
the lab still declares, within the limits Progress itself keeps; anything else is left out."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any

from server.world.checkpoints.progress import (
    MAX_ANSWER_BYTES,
    MAX_CAPTURE_BYTES,
    PNG_MAGIC,
    Answer,
    Progress,
    Record,
)

FORMAT = 1
MAX_FILE_BYTES = 8 * 1024 * 1024  # the evidence of a few checkpoints (tracks, timelines, a graph)


class SavedProgressError(ValueError):
    """A progress file that is not one (not JSON, another format, the wrong shapes)."""


@dataclass(frozen=True)
class Snapshot:
    """What to write, copied on the loop when the progress changed: the writer's thread reads this,
    never the live dicts (a Record, an Answer and the bytes are replaced on change, never edited)."""

    records: dict[str, Record]
    answers: dict[str, Answer]
    captures: dict[str, bytes] = field(default_factory=dict)

    @classmethod
    def of(cls, progress: Progress) -> Snapshot:
        return cls(dict(progress.records), dict(progress.answers), dict(progress.captures))


def encode(snapshot: Snapshot) -> bytes:
    records = {
        name: {"done_at_s": r.done_at_s, "times": r.times, "evidence": r.evidence}
        for name, r in snapshot.records.items()
    }
    answers = {
        qid: {"text": a.text, "saved_at_s": a.saved_at_s} for qid, a in snapshot.answers.items() if a.text
    }
    return json.dumps({"format": FORMAT, "records": records, "answers": answers}).encode()


def _number(value: Any) -> float | None:
    ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
    return float(value) if ok else None


def decode(raw: bytes, progress: Progress) -> int:
    """Put the records and answers of ``raw`` into ``progress``; how many were taken."""
    if len(raw) > MAX_FILE_BYTES:
        raise SavedProgressError(f"larger than {MAX_FILE_BYTES} bytes")
    try:
        body = json.loads(raw)
    except ValueError as exc:
        raise SavedProgressError(f"not JSON ({exc})") from None
    if not isinstance(body, dict) or body.get("format") != FORMAT:
        raise SavedProgressError(f"not a progress file of format {FORMAT}")
    records, answers = body.get("records"), body.get("answers")
    if not isinstance(records, dict) or not isinstance(answers, dict):
        raise SavedProgressError("no records and answers")
    declared = {c.name for c in progress.checkpoints}
    taken = 0
    for name, saved in records.items():
        if name not in declared or not isinstance(saved, dict):
            continue
        done_at_s, times, evidence = (
            _number(saved.get("done_at_s")),
            saved.get("times"),
            saved.get("evidence"),
        )
        if done_at_s is None or not isinstance(times, int) or times < 1 or not isinstance(evidence, dict):
            continue
        progress.records[name] = Record(done_at_s, evidence, times)
        taken += 1
    for qid, saved in answers.items():
        if qid not in progress.answers or not isinstance(saved, dict):
            continue
        text = saved.get("text")
        if not isinstance(text, str) or len(text.encode(errors="replace")) > MAX_ANSWER_BYTES:
            continue
        progress.answers[qid] = Answer(text, _number(saved.get("saved_at_s")))
        taken += 1
    return taken


def capture_ok(png: bytes) -> bool:
    """A capture Progress.capture would have taken."""
    return len(png) <= MAX_CAPTURE_BYTES and png.startswith(PNG_MAGIC)
