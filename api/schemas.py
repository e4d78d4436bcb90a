"""Request and response bodies of the REST API (pydantic at the boundary only)."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from server.publishers import MAX_RATE_HZ, MIN_RATE_HZ

MAX_NAME_CHARS = 256  # topic and type names


class TopicSummary(BaseModel):
    name: str = Field(examples=["/countdown"])
    type: str = Field(examples=["std_msgs/msg/Int64"])
    publishers: list[str] = Field(description="fully qualified names of the publishing nodes")
    subscribers: list[str] = Field(description="fully qualified names of the subscribing nodes")


class TopicDetail(TopicSummary):
    latest: dict[str, Any] | None = Field(description="the last message published, or null")
    latest_time: float | None = Field(description="when it was published (s, Unix epoch)")
    publish_count: int
    publisher_depths: list[int] = Field(description="QoS depth (keep-last) of each publisher")
    subscriber_depths: list[int] = Field(description="QoS depth (keep-last) of each subscription")


class PublishRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    topic: str = Field(max_length=MAX_NAME_CHARS, examples=["/abort_takeoff"])
    msg: dict[str, Any] = Field(default_factory=dict, examples=[{"data": True}])
    type: str | None = Field(
        default=None,
        max_length=MAX_NAME_CHARS,
        description="needed only when the topic does not exist yet",
        examples=["std_msgs/msg/Bool"],
    )


class PublishResult(BaseModel):
    topic: str
    type: str
    subscribers: int = Field(description="how many subscriptions received the message")


class Health(BaseModel):
    status: str
    launch: str
    nodes: int
    topics: int
    uptime_s: float


class RatePublisherRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    topic: str = Field(max_length=MAX_NAME_CHARS, examples=["/uav/input/position"])
    msg: dict[str, Any] = Field(default_factory=dict, examples=[{"x": 5.0, "y": 5.0, "z": 10.0}])
    type: str | None = Field(
        default=None, max_length=MAX_NAME_CHARS, description="needed only when the topic does not exist yet"
    )
    rate_hz: float = Field(
        ge=MIN_RATE_HZ, le=MAX_RATE_HZ, examples=[1.0], description="publishing rate, 0.01 to 1000 Hz"
    )
    enabled: bool = True


class RatePublisherUpdate(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    msg: dict[str, Any] | None = None
    rate_hz: float | None = Field(default=None, ge=MIN_RATE_HZ, le=MAX_RATE_HZ)
    enabled: bool | None = None


class RatePublisherInfo(BaseModel):
    id: str
    topic: str
    type: str
    msg: dict[str, Any]
    rate_hz: float
    enabled: bool
    count: int = Field(description="messages published so far")
