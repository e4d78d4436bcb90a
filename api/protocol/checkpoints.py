"""What the checkpoints routes take and answer (api/routes/checkpoints.py, docs/checkpoints.md): a
world's checkpoints and questions for the page's guide, an answer saved, the page's capture, the
signed report and its verification; and the class's table for the instructor."""

from __future__ import annotations

from typing import Annotated, Any, Literal, NotRequired

from pydantic import BaseModel, ConfigDict, Field, StringConstraints
from typing_extensions import TypedDict

CheckState = Literal["not_started", "in_progress", "done"]

WorldName = Annotated[str, StringConstraints(max_length=32)]
Tag = Annotated[str, StringConstraints(max_length=64)]


class AnswerBody(BaseModel):
    text: str = Field(description="the answer, at most 8 KiB of UTF-8")


class KnownCopies(BaseModel):
    model_config = ConfigDict(strict=True, extra="forbid")
    known: dict[WorldName, Tag] = Field(
        default_factory=dict,
        max_length=256,
        description="the tag of the copy the caller has of each world's progress",
    )


class VerifyResult(BaseModel):
    valid: bool
    reason: str = Field(description="valid, edited, signed by another server, or not a report")
    student: str | None


class Step(BaseModel):
    """One thing to do: what (``text``), how in the page (``page``: its buttons, panels, starting
    files), and the same in a terminal (``commands``, the alternative)."""

    text: str
    page: str
    commands: list[str]
    already: str | None = Field(
        description="what runs already, when the step's nodes run (the lab's launch started them): the "
        "guide shows it instead of asking"
    )


class Checkpoint(BaseModel):
    name: str
    title: str
    state: CheckState
    done_at: str | None = Field(description="when it was first done (ISO 8601, UTC)")
    times_done: int
    steps: list[Step]
    progress: str = Field(description="one short live line")
    evidence: dict[str, Any] | None = Field(
        description="what the check recorded when it was done (facts, timelines of TimelineEntry, a track)"
    )
    has_capture: bool = Field(description="the server keeps a picture the page sent")


class Question(TypedDict):
    id: str
    checkpoint: str
    text: str
    answer: str
    saved_at: str | None  # ISO 8601, UTC; null: never saved
    shows_graph: NotRequired[bool]  # the page shows the student's graph beside the box


class Checkpoints(BaseModel):
    checkpoints: list[Checkpoint]
    questions: list[Question]
    version: int = Field(description="rises on any change: ask with ?since= it")


class TimelineEntry(TypedDict):
    """One entry of an evidence's timeline: when (s, the lab's clock), what, its value, and who
    published it (its node, process, and whether that is the student's own code)."""

    t_s: float
    what: str
    value: Any
    by: NotRequired[str]
    process: NotRequired[str]
    student: NotRequired[bool]


class Captured(BaseModel):
    checkpoint: str
    captured: Literal[True]


class ReportCheckpoint(BaseModel):
    name: str
    title: str
    state: CheckState
    done_at: str | None
    times_done: int
    evidence: dict[str, Any] | None
    picture: str | None = Field(description="a data: URL: the page's capture, else the drone's track drawn")


class ReportSignature(BaseModel):
    algorithm: str
    key_id: str = Field(description="names the server's key, not the key")
    mac: str


class Report(BaseModel):
    """The signed report a student hands in, as its JSON file (its HTML page embeds the same)."""

    kind: str
    format: int
    student: str | None
    world: str | None
    generated_at: str
    checkpoints: list[ReportCheckpoint]
    questions: list[Question]
    signature: ReportSignature


class ClassCell(TypedDict):
    # unreachable: the world's world worker did not answer the class server in time
    state: Literal["not_started", "in_progress", "done", "unreachable"]
    done_at: str | None


class ClassStudent(TypedDict):
    name: str
    world: str
    cells: dict[str, ClassCell]
    answers: dict[str, str]
    joined: bool  # false: not joined since the class server started (listed from its saved progress)
    unreachable: NotRequired[str]  # why its world worker did not answer


class ClassCheckpoints(TypedDict):
    """Student × checkpoint, with the times each was done, and the answers."""

    checkpoints: list[str]
    students: list[ClassStudent]
    worker_errors: NotRequired[dict[str, str]]  # why each world worker that did not answer did not


class HandedOver(BaseModel):
    """A world's progress as one server hands it to another (server/world/checkpoints/handover.py)."""

    progress: dict[str, Any] = Field(description="the progress file's JSON")
    captures: dict[str, str] = Field(description="each checkpoint's capture, PNG in base64")


class ProgressCopy(BaseModel):
    tag: str
    progress: HandedOver


class ProgressCopies(BaseModel):
    worlds: dict[str, ProgressCopy] = Field(
        description="each world whose progress changed since its known tag"
    )


class Released(BaseModel):
    released: str = Field(description="the world")
    student: str = Field(description="the student whose progress it was")
