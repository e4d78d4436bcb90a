"""REST: health and the lab's own controls (reset the rocket)."""

from __future__ import annotations

import time
from typing import Any

from fastapi import APIRouter

from .deps import LabDep
from .responses import responses
from .schemas import Health

# Handlers are ``async def`` on purpose: the bus belongs to the event loop, and a plain ``def``
# handler would run in a worker thread and race the executor (timer heap, wake-up future).
router = APIRouter(prefix="/api", tags=["lab"], responses=responses())


@router.get("/health", response_model=Health)
async def health(lab: LabDep) -> dict[str, Any]:
    return {
        "status": "ok",
        "launch": lab.settings.launch,
        "nodes": len(lab.bus.nodes),
        "topics": len(lab.bus.topics),
        "uptime_s": round(time.monotonic() - lab.started_at, 3),
        "zenoh": lab.zenoh.status() if lab.zenoh is not None else None,
        "zenoh_error": lab.zenoh_error,
    }


@router.post("/rocket/reset", responses=responses(403))
async def reset_rocket(lab: LabDep) -> dict[str, str]:
    """Put the rocket back on the pad and restart the countdown (the rocket's nodes restart)."""
    lab.reset_rocket()
    return {"status": "reset"}
