"""Errors mapped once (api/errors.py): a bug is a 500 with a request id, logged with its traceback
and never sent; a 405 names every allowed method; NaN a node publishes goes out as null."""

from __future__ import annotations

import json
import logging
from typing import Any

import pytest
from labclient import LabClient, close_within

from api.errors import ERROR_STATUS, CloseCode, close_code, status_for
from node_runtime.msgs import Float64


def _lab(client: LabClient) -> Any:
    return client.http.app.state.lab  # type: ignore[attr-defined]


def test_errors_bug_in_a_route_is_500_with_request_id_traceback_logged_text_not_sent(
    rocket_lab: LabClient, monkeypatch: pytest.MonkeyPatch, caplog: pytest.LogCaptureFixture
) -> None:
    def broken(*_args: Any) -> None:
        raise KeyError("secret internals")

    monkeypatch.setattr(_lab(rocket_lab), "publish", broken)
    with caplog.at_level(logging.ERROR, logger="api.errors"):
        response = rocket_lab.http.post("/api/publish", json={"topic": "/countdown", "msg": {"data": 1}})

    assert response.status_code == 500
    body = response.json()
    assert body["request_id"] and body["request_id"] in body["detail"]
    assert "secret" not in response.text and "KeyError" not in response.text
    (record,) = [r for r in caplog.records if r.name == "api.errors"]
    assert body["request_id"] in record.getMessage()
    assert record.exc_info is not None and "secret internals" in str(record.exc_info[1])
    assert rocket_lab.healthy()


def test_errors_bug_in_a_websocket_closes_1011_with_request_id(
    rocket_lab: LabClient, monkeypatch: pytest.MonkeyPatch
) -> None:
    def broken(*_args: Any) -> None:
        raise ZeroDivisionError("secret")

    monkeypatch.setattr("api.websockets.echo.open_echo", broken)
    with rocket_lab.http.websocket_connect("/ws/topics/countdown") as ws:
        code, reason = close_within(ws)
    assert code == CloseCode.INTERNAL_ERROR
    assert "request id" in reason and "secret" not in reason


def test_errors_only_known_types_have_a_status_a_bare_value_error_is_a_bug() -> None:
    assert status_for(ValueError("x")) is None
    assert status_for(LookupError("x")) is None
    assert close_code(RuntimeError("x")) is None
    assert all(status_for(kind.__new__(kind)) == code for kind, code in ERROR_STATUS)


def test_errors_405_lists_every_method_of_the_path(rocket_lab: LabClient) -> None:
    response = rocket_lab.http.put("/api/publishers")
    assert response.status_code == 405
    assert set(response.headers["allow"].split(", ")) >= {"GET", "POST"}


def test_errors_nan_published_by_a_node_goes_out_as_null(rocket_lab: LabClient) -> None:
    lab = _lab(rocket_lab)
    pub = lab.api_node.create_publisher(Float64, "/odd", 10)  # a node may publish NaN; JSON cannot carry it
    with rocket_lab.http.websocket_connect("/ws/topics/odd") as ws:
        rocket_lab.http.portal.call(pub.publish, Float64(data=float("nan")))  # type: ignore[union-attr]
        frame = json.loads(ws.receive_text())
    assert frame["msg"] == {"data": None}
    response = rocket_lab.http.get("/api/topics/odd")
    assert response.status_code == 200
    assert response.json()["latest"] == {"data": None}


def test_errors_every_known_error_has_one_close_code_from_the_one_table() -> None:
    """A WebSocket refused for a reason gets the close code of the status a request gets for it:
    every status the error mapping gives has its code in the one table, and the app's own codes
    are 4000 plus that status (4400, a bad request, for the client errors without one of their own)."""
    from server.base.close_codes import CLOSE_FOR_STATUS

    for kind, status in ERROR_STATUS:
        assert status in CLOSE_FOR_STATUS, (kind.__name__, status)
    for status, code in CLOSE_FOR_STATUS.items():
        own = code == 4000 + status or (code == CloseCode.BAD_REQUEST and 400 <= status < 500)
        assert code < 4000 or own, (status, code)
    assert close_code(KeyError("x")) is None  # a bug has no code: the error net closes with 1011
