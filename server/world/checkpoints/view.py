"""One world's checkpoints as the API shows them (GET /api/checkpoints) and the class table reads."""

from __future__ import annotations

from collections.abc import Collection
from typing import Any

from server.world.checkpoints.declared import Step
from server.world.checkpoints.progress import Progress, iso

Lines = dict[str, tuple[bool, str]]  # by checkpoint: (started, progress line), from the watch


def state(progress: Progress, lines: Lines, name: str) -> str:
    if name in progress.records:
        return "done"
    return "in_progress" if lines.get(name, (False, ""))[0] else "not_started"


def questions(progress: Progress) -> list[dict[str, Any]]:
    out = []
    for checkpoint, question in progress.questions:
        answer = progress.answers[question.id]
        item: dict[str, Any] = {
            "id": question.id,
            "checkpoint": checkpoint.name,
            "text": question.text,
            "answer": answer.text,
            "saved_at": iso(answer.saved_at_s),
        }
        if question.shows_graph:
            item["shows_graph"] = True
        out.append(item)
    return out


def step_view(step: Step, running: Collection[str]) -> dict[str, Any]:
    """A step as the Guide shows it: the page's way first, the terminal's as the alternative, or
    what already runs when its nodes do (``running``: the names of the nodes running now)."""
    already = bool(step.running) and all(name in running for name in step.running)
    return {
        "text": step.text,
        "page": step.page,
        "commands": list(step.commands),
        "already": step.already if already else None,
    }


def world_view(
    progress: Progress, lines: Lines, version: int, running: Collection[str] = ()
) -> dict[str, Any]:
    checkpoints = []
    for c in progress.checkpoints:
        record = progress.records.get(c.name)
        checkpoints.append(
            {
                "name": c.name,
                "title": c.title,
                "state": state(progress, lines, c.name),
                "done_at": iso(record.done_at_s) if record is not None else None,
                "times_done": record.times if record is not None else 0,
                "steps": [step_view(s, running) for s in c.steps],
                "progress": lines.get(c.name, (False, ""))[1],
                "evidence": record.evidence if record is not None else None,
                "has_capture": c.name in progress.captures,
            }
        )
    return {"checkpoints": checkpoints, "questions": questions(progress), "version": version}
