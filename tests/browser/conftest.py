"""Fixtures for the browser tests: Chromium through Playwright's sync API, and the rocket lab server."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import pytest
from labserver import CHROMIUM_ARGS, REPO, LabServer, find_chromium
from playwright.sync_api import Browser, sync_playwright


@pytest.fixture(scope="module")
def rocket_server(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LabServer]:
    """The rocket lab, countdown 2 s after a (re)start, as `python -m server` runs it."""
    server = LabServer(
        ["--launch", "rocket", "start_delay:=2"], tmp_path_factory.mktemp("server") / "server.log"
    )
    try:
        server.wait_ready()
        yield server
    finally:
        server.stop()


@pytest.fixture(scope="session")
def chromium() -> Iterator[Browser]:
    """One Chromium for the session (a pytest-xdist worker's share of it); each test's page has a
    browser context of its own, so no cookie, storage or view choice passes from one to the next."""
    executable = find_chromium()
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=executable, args=CHROMIUM_ARGS)
        try:
            yield browser
        finally:
            browser.close()


@pytest.fixture
def screenshot_dir() -> Path:
    """Where screenshots go: $TELEOP_SCREENSHOTS, or artifacts/screenshots in the repository (git-ignored),
    where a person looks for them after a run."""
    folder = Path(os.environ.get("TELEOP_SCREENSHOTS") or REPO / "artifacts" / "screenshots")
    folder.mkdir(parents=True, exist_ok=True)
    return folder
