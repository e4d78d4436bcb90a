"""What the bag routes take and answer (api/routes/bag.py): ``ros2 bag record``, its bags, and
``ros2 bag play``."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict, Field

from server.peripherals.bag.manager import NAME as BAG_NAME
from server.peripherals.bag.player import MAX_RATE, MIN_RATE


class RecordRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    topics: list[str] = Field(default_factory=list, max_length=256, examples=[["/uav/sensors/gps"]])
    all: bool = Field(
        default=False, description="every topic but hidden ones, new ones too (ros2 bag record -a)"
    )
    name: str | None = Field(
        default=None,
        pattern=BAG_NAME.pattern,
        description="the bag's folder name; default rosbag2_YYYY_MM_DD-HH_MM_SS",
    )


class PlayRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    bag: str = Field(
        min_length=1,
        max_length=4096,
        description="a bag's name in the bag folder; a single lab on loopback also takes a path "
        "to a bag folder or .mcap file",
    )
    rate: float = Field(default=1.0, ge=MIN_RATE, le=MAX_RATE)
    loop: bool = False


class RecordingOut(BaseModel):
    """A recording of this run, going on or stopped."""

    name: str = Field(description="the bag's folder name in the bag folder")
    recording: bool = Field(description="still recording")
    topics: list[str] = Field(description="the topics recorded so far")
    messages: int = Field(description="messages written")
    counts: dict[str, int] = Field(description="messages written, by topic")
    dropped: int = Field(description="messages dropped: the writer fell behind")
    bytes: int = Field(description="bytes written")
    size_limited: bool = Field(description="the bag reached its size limit: nothing more is written")
    file: str = Field(description="the MCAP file's name in the bag's folder")


class StoredBag(BaseModel):
    """A bag an earlier run left in the bag folder."""

    model_config = ConfigDict(extra="forbid")
    name: str
    recording: Literal[False]


class BagDeleted(BaseModel):
    name: str
    deleted: Literal[True]


class PlayerOut(BaseModel):
    """A bag playing (or played): ``ros2 bag play``'s node."""

    id: str
    file: str = Field(description="the bag played")
    rate: float
    loop: bool
    published: int = Field(description="messages published so far")
    finished: bool
    skipped: dict[str, str] = Field(description="topics not played, and why")
