"""schemathesis with ``--checks all`` against one lab's whole API, on a live server
(schemathesis_run.py: the server and the run's bounds)."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from schemathesis_run import live_server, schemathesis


@pytest.fixture(scope="module")
def live_url(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    workdir = tmp_path_factory.mktemp("schemathesis_server")
    with live_server(workdir, "--launch", "rocket", "start_delay:=3600") as (url, _):
        yield url


def test_openapi_schemathesis_checks_all_pass(live_url: str) -> None:
    done = schemathesis(live_url, "schemathesis.toml")
    assert done.returncode == 0, done.stdout[-6000:] + done.stderr[-2000:]
