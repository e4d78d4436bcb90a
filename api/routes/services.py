"""REST: services, like ``ros2 service list -t`` and ``ros2 service call``."""

from __future__ import annotations

from fastapi import APIRouter

from api.deps import LabDep
from api.protocol.responses import NO_ANSWER, NOT_FOUND, TYPE_CONFLICT, responses
from api.protocol.services import ServiceCallRequest, ServiceCallResult, ServiceSummary
from node_runtime.transport.keys import EntityKind

# Handlers are ``async def``: the bus belongs to the event loop (see api/routes/topics.py).
router = APIRouter(prefix="/api", tags=["services"], responses=responses())


@router.get("/services")
async def list_services(lab: LabDep) -> list[ServiceSummary]:
    """Every service in the graph, served or called here or in another process."""
    found: dict[tuple[str, str], dict[str, list[str]]] = {}
    for channel in lab.bus.services.values():
        entry = found.setdefault((channel.name, channel.srv_type.TYPE), {"servers": [], "clients": []})
        entry["servers"] += [s.node.fully_qualified_name for s in channel.servers]
        entry["clients"] += [c.node.fully_qualified_name for c in channel.clients]
    remote = lab.remote_graph()
    if remote is not None:
        for e in remote.endpoints([EntityKind.SERVICE, EntityKind.CLIENT]):
            entry = found.setdefault((e.name, e.type_name), {"servers": [], "clients": []})
            entry["servers" if e.kind is EntityKind.SERVICE else "clients"].append(e.node)
    return [
        ServiceSummary(name=name, type=type_name, servers=entry["servers"], clients=entry["clients"])
        for (name, type_name), entry in sorted(found.items())
    ]


@router.post("/services/{name:path}", responses=responses(NOT_FOUND, TYPE_CONFLICT, NO_ANSWER, body=True))
async def call_service(name: str, body: ServiceCallRequest, lab: LabDep) -> ServiceCallResult:
    """Call a service (its name without the leading slash) and wait for the answer, as
    ``ros2 service call``; a call nobody answers in ``timeout_s`` is a 504."""
    service, srv_type, request = lab.service_caller.prepare(
        "/" + name.lstrip("/"), body.request, body.type, lab.remote_graph()
    )
    response = await lab.service_caller.call(service, srv_type, request, body.timeout_s)
    return ServiceCallResult(service=service, type=srv_type.TYPE, response=response.to_dict())
