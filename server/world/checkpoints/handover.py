"""A world's progress as one JSON value, handed from the place a world ran to the place it runs next.

A world worker that keeps its worlds' progress in a folder of its own (on another machine, with no
state folder shared with its class server) would take a world's ticks and answers with it when it
goes. So its class server keeps a copy of each such world's progress, asking for what changed at
every round of hellos (server/classroom/progress_copies.py), and hands its copy to the worker a
world starts on next. The value is the progress file's own JSON (saved.py) and each checkpoint's
capture in base64; ``tag`` tells one Progress's state from any other (its instance and version).
"""

from __future__ import annotations

import base64
import binascii
import json
from typing import Any

from server.world.checkpoints.declared import Checkpoint
from server.world.checkpoints.progress import Progress
from server.world.checkpoints.saved import SavedProgressError, Snapshot, capture_ok, decode, encode


def tag(progress: Progress) -> str:
    """Which Progress this is and how far it has changed: a copy with this tag is up to date."""
    return f"{progress.instance}.{progress.version}"


def to_wire(snapshot: Snapshot) -> dict[str, Any]:
    return {
        "progress": json.loads(encode(snapshot)),
        "captures": {name: base64.b64encode(png).decode() for name, png in snapshot.captures.items()},
    }


def from_wire(body: Any, checkpoints: tuple[Checkpoint, ...]) -> Snapshot:
    """The progress ``body`` holds, checked as a progress file is read; SavedProgressError for
    anything else (not the shape, a checkpoint this lab does not have, a capture that is no PNG)."""
    if not isinstance(body, dict) or not isinstance(body.get("progress"), dict):
        raise SavedProgressError("not a handed-over progress (an object with 'progress')")
    captures = body.get("captures", {})
    if not isinstance(captures, dict):
        raise SavedProgressError("'captures' is not an object")
    progress = Progress(checkpoints)
    decode(json.dumps(body["progress"]).encode(), progress)
    known = {c.name for c in checkpoints}
    for name, text in captures.items():
        if name not in known or not isinstance(text, str):
            raise SavedProgressError(f"a capture of {name!r}, which is no checkpoint of this lab")
        try:
            png = base64.b64decode(text, validate=True)
        except (binascii.Error, ValueError):
            raise SavedProgressError(f"the capture of {name!r} is not base64") from None
        if not capture_ok(png):
            raise SavedProgressError(f"the capture of {name!r} is not a PNG within the size limit")
        progress.captures[name] = png
    return Snapshot.of(progress)
