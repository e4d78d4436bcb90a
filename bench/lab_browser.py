"""For the page benches: the lab (``--launch all``, the rocket waiting on its pad) and one
headless Chromium on software WebGL, both ended on the way out."""

from __future__ import annotations

import sys
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from live_server import LiveServer
from machine import CHROMIUM, CHROMIUM_ARGS


def have_chromium() -> bool:
    """Whether Debian's Chromium is there; says what to install when it is not."""
    if Path(CHROMIUM).is_file():
        return True
    print(f"no Chromium at {CHROMIUM}: apt-get install chromium", file=sys.stderr)
    return False


@contextmanager
def lab_and_chromium() -> Iterator[tuple[LiveServer, Any]]:
    """A lab server in a folder of its own and a Chromium (Playwright's ``Browser``)."""
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as workdir:
        server = LiveServer(Path(workdir), "all", "start_delay:=3600")
        try:
            with sync_playwright() as playwright:
                browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
                try:
                    yield server, browser
                finally:
                    browser.close()
        finally:
            server.stop()
