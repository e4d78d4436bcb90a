"""The instructor's table of the class: student × checkpoint, with times; as JSON or CSV; and every
student's report in one zip. A student listed from their saved progress alone (not joined since the
class server started) has ``joined`` false, and their cells say what their files keep."""

from __future__ import annotations

import csv
import io
import zipfile
from collections.abc import Sequence
from typing import Any

from server.world.checkpoints.progress import Progress, iso
from server.world.checkpoints.view import Lines, state

Row = tuple[str, Progress, Lines]  # (world name, its progress, its watch's lines)


def table(names: Sequence[str], rows: Sequence[Row], saved: Sequence[Row] = ()) -> dict[str, Any]:
    """``rows``: the worlds joined now; ``saved``: the students not joined since the start."""
    students = []
    for (world, progress, lines), joined in [*((r, True) for r in rows), *((r, False) for r in saved)]:
        cells = {}
        for name in names:
            record = progress.records.get(name)
            cells[name] = {
                "state": state(progress, lines, name),
                "done_at": iso(record.done_at_s) if record is not None else None,
            }
        students.append(
            {
                "name": progress.student or world,
                "world": world,
                "cells": cells,
                "answers": {qid: a.text for qid, a in progress.answers.items()},
                "joined": joined,
            }
        )
    return {"checkpoints": list(names), "students": students}


def _cell(value: str) -> str:
    """A student's text as a spreadsheet shows it, never as a formula it would run."""
    return "'" + value if value[:1] in ("=", "+", "-", "@", "\t", "\r") else value


def table_csv(view: dict[str, Any]) -> str:
    out = io.StringIO()
    writer = csv.writer(out)
    names = view["checkpoints"]
    qids = sorted({q for s in view["students"] for q in s["answers"]})
    states, times = [f"{n} state" for n in names], [f"{n} done at" for n in names]
    writer.writerow(
        ["student", "world", *states, *times, *qids, "joined"]
    )  # "joined" last: columns as before
    for s in view["students"]:
        writer.writerow(
            [
                _cell(s["name"]),
                s["world"],
                *[s["cells"].get(n, {}).get("state", "") for n in names],
                *[s["cells"].get(n, {}).get("done_at") or "" for n in names],
                *[_cell(s["answers"].get(q, "")) for q in qids],
                "yes" if s.get("joined", True) else "no",
            ]
        )
    return out.getvalue()


def reports_zip(files: Sequence[tuple[str, bytes]]) -> bytes:
    out = io.BytesIO()
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as archive:
        for name, data in files:
            archive.writestr(name, data)
    return out.getvalue()
