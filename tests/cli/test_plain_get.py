"""``ros2lab run``'s GETs over a plain socket (server/cli/plain_get.py) answer as
``LabClient.get``'s do, against the real app in its own process: the same JSON, the same
one-line errors (the app's detail, its 429's waits and ticket read whatever the headers' case),
none where nothing listens, a bounded wait where nothing answers; what is not an HTTP answer, or
is too big, is one error; a token that would break the request's headers is refused before any
is sent; a lab behind TLS keeps httpx."""

from __future__ import annotations

import socket
import threading
from collections.abc import Iterator

import pytest
from support.app import App, free_port

from server.cli.client import ApiError, CliError, LabClient, NoServerError
from server.cli.plain_get import MAX_ANSWER_BYTES, PlainGet, getter_for


@pytest.fixture(scope="module")
def app(tmp_path_factory: pytest.TempPathFactory) -> Iterator[App]:
    app = App(tmp_path_factory.mktemp("plain_get"), "--launch", "rocket")
    try:
        yield app
    finally:
        app.stop()


def test_answers_as_the_labs_client_does(app: App) -> None:
    plain, client = PlainGet(app.url, {}), LabClient(app.url)
    with client:
        for path, params in (("/api/topics", None), ("/api/zenoh/join", {"start": "false"})):
            assert plain.get(path, params) == client.get(path, params)
        for path in ("/api/topics/no_such_topic", "/api/no_such_route"):
            with pytest.raises(ApiError) as by_plain:
                plain.get(path)
            with pytest.raises(ApiError) as by_client:
                client.get(path)
            assert (by_plain.value.status, str(by_plain.value), by_plain.value.no_route) == (
                by_client.value.status,
                str(by_client.value),
                by_client.value.no_route,
            )


def test_a_paced_starts_wait_and_ticket_are_read_from_the_labs_headers(app: App) -> None:
    """The app writes its header names in lower case; they are read by name all the same."""
    plain = PlainGet(app.url, {})
    params = {"start": "true", "turn": "new"}
    refused = None
    for _ in range(3):  # the lab's one slot is held 0.75 s from the first: one of the next is told to wait
        try:
            plain.get("/api/zenoh/join", params)
        except ApiError as exc:
            refused = exc
            break
    assert refused is not None and refused.status == 429, "no start was paced"
    assert refused.retry_after_s is not None and 0 < refused.retry_after_s <= 0.75 + 0.01
    assert refused.retry_after_s != int(refused.retry_after_s)  # the milliseconds, not Retry-After's seconds
    assert refused.turn and len(refused.turn) <= 64


def test_where_nothing_listens_or_nothing_answers() -> None:
    with pytest.raises(NoServerError):
        PlainGet(f"http://127.0.0.1:{free_port()}", {}).get("/api/health")
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen(1)
        plain = PlainGet(f"http://127.0.0.1:{silent.getsockname()[1]}", {})
        with pytest.raises(CliError, match="GET /api/health: ReadTimeout"):
            plain.get("/api/health", timeout_s=0.3)


def test_a_lab_behind_tls_is_asked_through_httpx() -> None:
    client = LabClient("https://lab.example")
    assert getter_for(client) is client
    plain = getter_for(LabClient("http://127.0.0.1:9"))
    assert isinstance(plain, PlainGet)
    with pytest.raises(ValueError, match="http://"):
        PlainGet("https://lab.example", {})


def answering(reply: bytes) -> tuple[socket.socket, threading.Thread, list[bytes]]:
    """A stand-in on 127.0.0.1 that reads one request, sends ``reply`` and closes."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    requests: list[bytes] = []

    def serve() -> None:
        conn, _ = server.accept()
        with conn:
            requests.append(conn.recv(65536))
            conn.sendall(reply)

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    return server, thread, requests


def test_what_is_not_an_http_answer_or_is_too_big_is_one_error_not_a_crash() -> None:
    for reply, match in (
        (b"SSH-2.0-OpenSSH_9.2\r\n", "not an HTTP answer"),
        (b"HTTP/1.1 2OO OK\r\n\r\n{}", "not an HTTP answer"),
        (b"HTTP/1.1 200 OK\r\nContent-Type: application/json\r\n", "not an HTTP answer"),  # cut short
        (b"HTTP/1.1 200 OK\r\n\r\n" + b" " * (MAX_ANSWER_BYTES + 1), f"over {MAX_ANSWER_BYTES} bytes"),
    ):
        server, thread, requests = answering(reply)
        with server:
            with pytest.raises(CliError, match=match):
                PlainGet(f"http://127.0.0.1:{server.getsockname()[1]}", {}).get("/api/health", timeout_s=10)
            thread.join(timeout=10)
        assert requests and requests[0].startswith(b"GET /api/health HTTP/1.0\r\n")


def test_the_request_carries_its_token_and_a_token_that_would_break_its_headers_is_refused() -> None:
    server, thread, requests = answering(b'HTTP/1.1 200 OK\r\nContent-Length: 11\r\n\r\n{"ok": true}')
    with server:
        url = f"http://127.0.0.1:{server.getsockname()[1]}"
        assert PlainGet(url, {"Authorization": "Bearer s3cret"}).get("/api/x", {"a": "b c"}) == {"ok": True}
        thread.join(timeout=10)
    head = requests[0].decode().split("\r\n")
    assert head[0] == "GET /api/x?a=b+c HTTP/1.0" and "Authorization: Bearer s3cret" in head
    with pytest.raises(CliError, match="Authorization header"):
        PlainGet(url, {"Authorization": "Bearer s3cret\r\nX-Forged: 1"})
