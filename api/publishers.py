"""REST: periodic publishers, like rqt's Message Publisher (start, list, change, stop)."""

from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException, status

from server.publishers import UnknownPublisherError

from .deps import LabDep
from .errors import http_error
from .schemas import RatePublisherInfo, RatePublisherRequest, RatePublisherUpdate
from .topics import reject_non_finite

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
router = APIRouter(prefix="/api/publishers", tags=["publishers"])


def _error(exc: Exception) -> HTTPException:
    if isinstance(exc, UnknownPublisherError):
        return HTTPException(status.HTTP_404_NOT_FOUND, str(exc))
    return http_error(exc)


@router.post("", response_model=RatePublisherInfo, status_code=status.HTTP_201_CREATED)
async def start(body: RatePublisherRequest, lab: LabDep) -> dict[str, Any]:
    """Publish ``msg`` on ``topic`` every 1/rate_hz s (the first one at once); returns its id."""
    try:
        reject_non_finite(body.msg)
        return lab.publishers.start(body.topic, body.msg, body.type, body.rate_hz, body.enabled).describe()
    except Exception as exc:
        raise _error(exc) from exc


@router.get("", response_model=list[RatePublisherInfo])
async def list_publishers(lab: LabDep) -> list[dict[str, Any]]:
    return [item.describe() for item in lab.publishers.items.values()]


@router.get("/{publisher_id}", response_model=RatePublisherInfo)
async def get_publisher(publisher_id: str, lab: LabDep) -> dict[str, Any]:
    try:
        return lab.publishers.get(publisher_id).describe()
    except Exception as exc:
        raise _error(exc) from exc


@router.patch("/{publisher_id}", response_model=RatePublisherInfo)
async def update(publisher_id: str, body: RatePublisherUpdate, lab: LabDep) -> dict[str, Any]:
    """Enable, disable, or change the rate or the message of a running publisher."""
    try:
        if body.msg is not None:
            reject_non_finite(body.msg)
        return lab.publishers.update(
            publisher_id, enabled=body.enabled, rate_hz=body.rate_hz, msg=body.msg
        ).describe()
    except Exception as exc:
        raise _error(exc) from exc


@router.delete("/{publisher_id}", response_model=RatePublisherInfo)
async def stop(publisher_id: str, lab: LabDep) -> dict[str, Any]:
    try:
        return lab.publishers.stop(publisher_id).describe()
    except Exception as exc:
        raise _error(exc) from exc
