"""REST: periodic publishers, like rqt's Message Publisher (start, list, change, stop)."""

from __future__ import annotations

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
    status_code=status.HTTP_201_CREATED,
    responses=responses(NOT_FOUND, TYPE_CONFLICT, TOO_MANY, body=True),
)
async def start(body: RatePublisherRequest, lab: LabDep) -> RatePublisherInfo:
    """Publish ``msg`` on ``topic`` every 1/rate_hz s (the first one at once); returns its id."""
    item = lab.publishers.start(body.topic, body.msg, body.type, body.rate_hz, body.enabled)
    return RatePublisherInfo.model_validate(item.describe())


@router.get("")
async def list_publishers(lab: LabDep) -> list[RatePublisherInfo]:
    return [RatePublisherInfo.model_validate(item.describe()) for item in lab.publishers.items.values()]


@router.get("/{publisher_id}", responses=responses(NOT_FOUND))
async def get_publisher(publisher_id: str, lab: LabDep) -> RatePublisherInfo:
    return RatePublisherInfo.model_validate(lab.publishers.get(publisher_id).describe())


@router.patch("/{publisher_id}", responses=responses(NOT_FOUND, body=True))
async def update(publisher_id: str, body: RatePublisherUpdate, lab: LabDep) -> RatePublisherInfo:
    """Enable, disable, or change the rate or the message of a running publisher."""
    item = lab.publishers.update(publisher_id, enabled=body.enabled, rate_hz=body.rate_hz, msg=body.msg)
    return RatePublisherInfo.model_validate(item.describe())


@router.delete("/{publisher_id}", responses=responses(NOT_FOUND, 403))
async def stop(publisher_id: str, lab: LabDep) -> RatePublisherInfo:
    return RatePublisherInfo.model_validate(lab.publishers.stop(publisher_id).describe())
