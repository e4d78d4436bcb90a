"""client.py: the API's answers and failures as the CLI reports them (no server: a mock transport)."""

from __future__ import annotations

from typing import Any

import httpx
import pytest

from server.cli.client import (
    CLOSE_NOT_FOUND,
    ApiError,
    CliError,
    LabClient,
    NoServerError,
    describe_detail,
)


def client_answering(status: int, body: Any = None, text: str | None = None) -> LabClient:
    def handler(request: httpx.Request) -> httpx.Response:
        if text is not None:
            return httpx.Response(status, text=text)
        return httpx.Response(status, json=body)

    return LabClient("http://lab.test", transport=httpx.MockTransport(handler))


def test_close_code_for_not_found_matches_the_api() -> None:
    from api.errors import CloseCode

    assert CLOSE_NOT_FOUND == CloseCode.NOT_FOUND


def test_get_success_returns_json() -> None:
    assert client_answering(200, [{"name": "/countdown"}]).get("/api/topics") == [{"name": "/countdown"}]


@pytest.mark.parametrize("status", [404, 409, 422])
def test_request_api_error_reports_the_servers_detail_alone(status: int) -> None:
    with pytest.raises(ApiError) as caught:
        client_answering(status, {"detail": "data: std_msgs/msg/Bool has no field 'dta'"}).post(
            "/api/publish", {}
        )
    assert str(caught.value) == "data: std_msgs/msg/Bool has no field 'dta'"
    assert caught.value.status == status
    assert caught.value.exit_code == 1


def test_request_unexpected_status_reports_method_path_status_and_detail() -> None:
    with pytest.raises(ApiError, match=r"^GET /api/topics: HTTP 500: boom$"):
        client_answering(500, {"detail": "boom"}).get("/api/topics")
    with pytest.raises(ApiError, match=r"^GET /api/topics: HTTP 502: bad gateway$"):
        client_answering(502, text="bad gateway").get("/api/topics")


def test_request_missing_route_says_the_server_has_no_such_endpoint() -> None:
    with pytest.raises(ApiError, match="no such endpoint") as caught:
        client_answering(404, {"detail": "Not Found"}).get("/api/hz/sensor_vel")
    assert caught.value.no_route


def test_describe_detail_validation_errors_joined_with_their_fields() -> None:
    detail = [
        {"loc": ["body", "rate_hz"], "msg": "Input should be greater than 0", "type": "greater_than"},
        {"loc": ["body"], "msg": "Field required"},
    ]
    assert describe_detail(detail) == "rate_hz: Input should be greater than 0; Field required"


def test_request_connection_refused_is_no_server_with_exit_code_2() -> None:
    def refuse(request: httpx.Request) -> httpx.Response:
        raise httpx.ConnectError("Connection refused", request=request)

    client = LabClient("http://127.0.0.1:9", transport=httpx.MockTransport(refuse))
    with pytest.raises(NoServerError) as caught:
        client.get("/api/topics")
    assert str(caught.value) == "no lab server at http://127.0.0.1:9 (start it with: bash scripts/run.sh)"
    assert caught.value.exit_code == 2


def test_request_timeout_is_a_one_line_error() -> None:
    def slow(request: httpx.Request) -> httpx.Response:
        raise httpx.ReadTimeout("timed out", request=request)

    client = LabClient("http://lab.test", transport=httpx.MockTransport(slow))
    with pytest.raises(CliError, match="GET /api/topics: ReadTimeout"):
        client.get("/api/topics")


@pytest.mark.parametrize(
    ("base", "ws"),
    [
        ("http://127.0.0.1:8000", "ws://127.0.0.1:8000/ws/topics/countdown?queue_length=5"),
        ("https://lab.example/", "wss://lab.example/ws/topics/countdown?queue_length=5"),
        ("http://host/prefix", "ws://host/prefix/ws/topics/countdown?queue_length=5"),
    ],
)
def test_ws_url_follows_the_http_scheme_and_path(base: str, ws: str) -> None:
    assert LabClient(base).ws_url("/ws/topics/countdown", {"queue_length": 5}) == ws
