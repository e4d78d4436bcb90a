"""REST: services, like ``ros2 service list -t`` and ``ros2 service call``."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter
from pydantic import BaseModel, ConfigDict, Field

from api.deps import LabDep
from api.protocol.responses import NO_ANSWER, NOT_FOUND, TYPE_CONFLICT, responses
from node_runtime.transport.keys import EntityKind

# Handlers are ``async def``: the bus belongs to the event loop (see api/routes/topics.py).
router = APIRouter(prefix="/api", tags=["services"], responses=responses())
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


@router.get("/services", response_model=list[ServiceSummary])
async def list_services(lab: LabDep) -> list[dict[str, Any]]:
    """Every service in the graph, served or called here or in another process."""
    found: dict[tuple[str, str], dict[str, Any]] = {}
    for channel in lab.bus.services.values():
        entry = found.setdefault((channel.name, channel.srv_type.TYPE), {"servers": [], "clients": []})
        entry["servers"] += [s.node.fully_qualified_name for s in channel.servers]
        entry["clients"] += [c.node.fully_qualified_name for c in channel.clients]
    remote = lab.remote_graph()
    if remote is not None:
        for e in remote.endpoints([EntityKind.SERVICE, EntityKind.CLIENT]):
            entry = found.setdefault((e.name, e.type_name), {"servers": [], "clients": []})
            entry["servers" if e.kind is EntityKind.SERVICE else "clients"].append(e.node)
    return [{"name": name, "type": type_name, **entry} for (name, type_name), entry in sorted(found.items())]


@router.post(
    "/services/{name:path}",
    response_model=ServiceCallResult,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, NO_ANSWER, body=True),
)
async def call_service(name: str, body: ServiceCallRequest, lab: LabDep) -> dict[str, Any]:
    """Call a service (its name without the leading slash) and wait for the answer, as
    ``ros2 service call``; a call nobody answers in ``timeout_s`` is a 504."""
    service, srv_type, request = lab.service_caller.prepare(
        "/" + name.lstrip("/"), body.request, body.type, lab.remote_graph()
    )
    response = await lab.service_caller.call(service, srv_type, request, body.timeout_s)
    return {"service": service, "type": srv_type.TYPE, "response": response.to_dict()}
