"""REST: periodic publishers, like rqt's Message Publisher (start, list, change, stop)."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, status

from api.deps import LabDep
from api.protocol.responses import NOT_FOUND, TOO_MANY, TYPE_CONFLICT, responses
from api.protocol.schemas import RatePublisherInfo, RatePublisherRequest, RatePublisherUpdate

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
# Errors are mapped in api/errors.py; handlers do not catch.
router = APIRouter(prefix="/api/publishers", tags=["publishers"], responses=responses())


@router.post(
    "",
    response_model=RatePublisherInfo,
    status_code=status.HTTP_201_CREATED,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, TOO_MANY, body=True),
)
async def start(body: RatePublisherRequest, lab: LabDep) -> dict[str, Any]:
    """Publish ``msg`` on ``topic`` every 1/rate_hz s (the first one at once); returns its id."""
    return lab.publishers.start(body.topic, body.msg, body.type, body.rate_hz, body.enabled).describe()


@router.get("", response_model=list[RatePublisherInfo])
async def list_publishers(lab: LabDep) -> list[dict[str, Any]]:
    return [item.describe() for item in lab.publishers.items.values()]


@router.get("/{publisher_id}", response_model=RatePublisherInfo, responses=responses(NOT_FOUND))
async def get_publisher(publisher_id: str, lab: LabDep) -> dict[str, Any]:
    return lab.publishers.get(publisher_id).describe()


@router.patch("/{publisher_id}", response_model=RatePublisherInfo, responses=responses(NOT_FOUND, body=True))
async def update(publisher_id: str, body: RatePublisherUpdate, lab: LabDep) -> dict[str, Any]:
    """Enable, disable, or change the rate or the message of a running publisher."""
    item = lab.publishers.update(publisher_id, enabled=body.enabled, rate_hz=body.rate_hz, msg=body.msg)
    return item.describe()


@router.delete("/{publisher_id}", response_model=RatePublisherInfo, responses=responses(NOT_FOUND, 403))
async def stop(publisher_id: str, lab: LabDep) -> dict[str, Any]:
    return lab.publishers.stop(publisher_id).describe()
