"""The page's record button in a real headless Chromium: Record flight, Stop recording, and the
download link serves the bag's MCAP file."""

from __future__ import annotations

import shutil

import pytest
from labpage import HTTP_TIMEOUT_S
from labserver import REPO, LabServer
from playwright.sync_api import Page
from support.http import HTTP
from test_rocket_browser import open_lab_page, page, wait_responsive, wait_until  # noqa: F401  (page is a fixture)

pytestmark = pytest.mark.browser
MCAP_MAGIC = b"\x89MCAP0\r\n"


def recordings(server: LabServer) -> list[dict[str, object]]:
    return list(HTTP.get(f"{server.url}/api/bag/recordings", timeout=HTTP_TIMEOUT_S).json())


def test_record_button_records_and_the_link_downloads_the_mcap(page: Page, rocket_server: LabServer) -> None:  # noqa: F811
    before = {r["name"] for r in recordings(rocket_server)}
    open_lab_page(page, rocket_server)
    wait_responsive(page)
    page.get_by_text("Recording", exact=True).click()
    page.get_by_role("button", name="Record flight").click()
    new = wait_until(
        lambda: [r for r in recordings(rocket_server) if r["name"] not in before and r["recording"]],
        "a recording to start",
    )
    name = str(new[0]["name"])
    wait_until(
        lambda: any(r["name"] == name and int(r["messages"]) > 20 for r in recordings(rocket_server)),  # type: ignore[call-overload]
        "the recording to hear the rocket's topics",
    )
    page.get_by_role("button", name="Stop recording").click()
    link = page.get_by_role("link", name=f"Download {name}")
    link.wait_for()
    href = link.get_attribute("href")
    assert href == f"/api/bag/recordings/{name}/download"
    body = HTTP.get(rocket_server.url + href, timeout=10.0).content
    assert body.startswith(MCAP_MAGIC) and len(body) > 1000
    shutil.rmtree(REPO / "bags" / name, ignore_errors=True)  # the server runs in the repository
