"""The app leaves FastAPI's own OpenTelemetry off whatever the environment says
(server/app.py): an environment asking FastAPI to export request traces to an OTLP endpoint
makes the lab try nothing. Its peer, a bare FastAPI app in the same environment, tries to set up
the export at its start (here it fails for want of the SDK, which the lab does not install, and
says so; with the SDK it would send every request's trace to that endpoint)."""

from __future__ import annotations

import logging

import pytest
from fastapi import FastAPI
from fastapi.testclient import TestClient

from server.app import create_app
from server.host.settings import LabSettings, Listening, Settings

TRIED = "automatic telemetry configuration failed"  # what FastAPI logs when its set-up cannot export
# Port 9 (discard) on loopback: were anything sent, it would go nowhere beyond this machine.
OTEL_ENV = {
    "FASTAPI_OTEL_AUTO_CONFIGURE": "true",
    "OTEL_EXPORTER_OTLP_ENDPOINT": "http://127.0.0.1:9",
}


@pytest.fixture
def otel_env(monkeypatch: pytest.MonkeyPatch) -> None:
    for name, value in OTEL_ENV.items():
        monkeypatch.setenv(name, value)


@pytest.mark.usefixtures("otel_env")
def test_the_lab_starts_and_answers_with_fastapi_telemetry_asked_for_in_the_environment(
    caplog: pytest.LogCaptureFixture,
) -> None:
    settings = Settings(
        listen=Listening(allowed_hosts=("testserver",)),
        lab=LabSettings(launch="rocket", viewer=False, zenoh=None),
    )
    app = create_app(settings)
    with caplog.at_level(logging.WARNING), TestClient(app) as client:
        assert client.get("/api/health").status_code == 200
    assert not [r for r in caplog.records if TRIED in r.getMessage()]
    config = app._telemetry  # what FastAPI reads at start and on every request
    assert not any(config[key] for key in ("auto_configure", "tracing", "metrics", "logs"))


@pytest.mark.usefixtures("otel_env")
def test_a_bare_fastapi_app_in_that_environment_tries_to_set_up_the_export(
    caplog: pytest.LogCaptureFixture,
) -> None:
    app = FastAPI()
    assert app._telemetry["auto_configure"] is True
    with caplog.at_level(logging.WARNING), TestClient(app):
        pass
    assert [r for r in caplog.records if TRIED in r.getMessage()]
