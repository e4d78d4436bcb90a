"""``/tools``: the lab's rqt in a page (graph, node and topic info, rate, echo), from static/."""

from __future__ import annotations

from pathlib import Path

from fastapi import APIRouter
from fastapi.responses import FileResponse, HTMLResponse

router = APIRouter(include_in_schema=False)
TOOLS_HTML = Path(__file__).resolve().parents[2] / "static" / "tools.html"
# Everything the page needs comes from this server: no CDN, so it works offline, and nothing else
# may be loaded, framed or connected to.
CONTENT_SECURITY_POLICY = (
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data:; "
    "connect-src 'self'; frame-ancestors 'none'; base-uri 'none'; form-action 'none'"
)


@router.get("/tools", response_class=HTMLResponse)
async def tools_page() -> FileResponse:
    return FileResponse(
        TOOLS_HTML,
        media_type="text/html",
        headers={"Cache-Control": "no-cache", "Content-Security-Policy": CONTENT_SECURITY_POLICY},
    )
