"""What the services' routes take and answer (api/routes/services.py): ``ros2 service list -t`` and
``ros2 service call``."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

MAX_TIMEOUT_S = 60.0


class ServiceSummary(BaseModel):
    name: str = Field(examples=["/rocket/reset"])
    type: str = Field(examples=["std_srvs/srv/Trigger"])
    servers: list[str] = Field(description="fully qualified names of the serving nodes")
    clients: list[str] = Field(description="fully qualified names of the nodes with a client")


class ServiceCallRequest(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)
    request: dict[str, Any] = Field(default_factory=dict, examples=[{}])
    type: str | None = Field(
        default=None,
        description="optional: checked against the type the service is served with",
        examples=["std_srvs/srv/Trigger"],
    )
    timeout_s: float = Field(
        default=5.0, gt=0, le=MAX_TIMEOUT_S, description="how long to wait for the answer"
    )


class ServiceCallResult(BaseModel):
    service: str
    type: str
    response: dict[str, Any]
