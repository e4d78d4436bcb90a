"""A checkpoint as a small declared value: its name, title, steps, questions and a check.

A check is a little state machine over the lab's events (events.py): ``feed`` each event and
``tick`` now and then; either returns the evidence when the check is met. A lab adds its own
checkpoint by declaring one of these (docs/checkpoints.md) — nothing else changes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from server.world.checkpoints.events import Event

Evidence = dict[str, Any]  # JSON-ready: timelines, tracks, texts; the watcher adds the graph


@dataclass(frozen=True)
class Step:
    """One thing to do. ``text`` says what; ``page`` says how in the page, naming its own controls
    as it shows them (the Code view, Run, Reset rocket, the Message Publisher panel, the starting
    files); ``commands`` do the same in a terminal, the alternative. A step whose ``running`` nodes
    all run already (the lab's launch started them) shows ``already`` instead of asking again."""

    text: str
    commands: tuple[str, ...] = ()
    page: str = ""
    running: tuple[str, ...] = ()  # fully qualified node names
    already: str = ""


@dataclass(frozen=True)
class Question:
    id: str
    text: str
    shows_graph: bool = False  # the page shows the student's graph beside the answer box


class Check(Protocol):
    """One world's running check. Never blocks, never raises on odd input, keeps bounded state."""

    @property
    def started(self) -> bool:
        """Something towards it happened (the guide shows "in progress")."""
        ...

    def feed(self, event: Event) -> Evidence | None: ...

    def tick(self, now_s: float) -> Evidence | None: ...

    def progress(self, now_s: float) -> str:
        """One short live line for the guide."""
        ...


@dataclass(frozen=True)
class Checkpoint:
    """``check`` makes a fresh check (one per world, and again when its world is reset)."""

    name: str
    title: str
    steps: tuple[Step, ...]
    check: Callable[[], Check]
    questions: tuple[Question, ...] = ()
    wants_graph: bool = False  # its evidence carries the graph at the moment it was met
