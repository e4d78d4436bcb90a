"""Per-app limits with clear errors (429, or 1013 on a socket), and refusals that leave nothing
behind: no node, no publisher, no launch, no logger per refused or closed socket."""

from __future__ import annotations

import logging
from collections.abc import Callable
from typing import Any

from labclient import LabClient, close_within

from api.errors import CloseCode


def _lab(client: LabClient) -> Any:
    return client.http.app.state.lab  # type: ignore[attr-defined]


def _node_names(client: LabClient) -> set[str]:
    return {n.fully_qualified_name for n in _lab(client).bus.nodes}


def test_limits_publishers_beyond_the_limit_429_and_nothing_more_runs(
    make_lab: Callable[..., LabClient],
) -> None:
    lab = make_lab(max_publishers=2)
    body = {"topic": "/countdown", "msg": {"data": 3}, "rate_hz": 1.0}
    assert [lab.http.post("/api/publishers", json=body).status_code for _ in range(2)] == [201, 201]

    response = lab.http.post("/api/publishers", json=body)

    assert response.status_code == 429
    assert "at most 2 periodic publishers" in response.json()["detail"]
    assert len(lab.http.get("/api/publishers").json()) == 2


def test_limits_publisher_rate_that_would_overflow_the_period_refused_nothing_running(
    rocket_lab: LabClient,
) -> None:
    response = rocket_lab.http.post(
        "/api/publishers", json={"topic": "/countdown", "msg": {"data": 3}, "rate_hz": 5e-324}
    )
    assert response.status_code == 422
    assert rocket_lab.http.get("/api/publishers").json() == []
    assert rocket_lab.publish_count("/countdown") == 0


def test_limits_launches_beyond_the_limit_429_and_nothing_started(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(max_launch_groups=1)
    run = {"package": "rocketship", "executable": "countdown", "name": "second_countdown"}
    assert lab.http.post("/api/run", json=run).status_code == 201
    before = _node_names(lab)

    refused_run = lab.http.post("/api/run", json={**run, "name": "third_countdown"})
    refused_launch = lab.http.post("/api/launch", json={"package": "rocketship", "file": "rocket.launch"})

    assert (refused_run.status_code, refused_launch.status_code) == (429, 429)
    assert "at most 1 launches and runs" in refused_run.json()["detail"]
    assert _node_names(lab) == before


def test_limits_run_with_an_invalid_node_name_422_before_anything_starts(rocket_lab: LabClient) -> None:
    before = _node_names(rocket_lab)
    response = rocket_lab.http.post(
        "/api/run", json={"package": "rocketship", "executable": "countdown", "name": "9lives"}
    )
    assert response.status_code == 422
    assert "9lives" in response.json()["detail"]
    assert _node_names(rocket_lab) == before
    assert rocket_lab.http.get("/api/launches").json() == []


def test_limits_echo_sockets_beyond_the_limit_closed_1013(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab(max_echo_sockets=2)
    with (
        lab.http.websocket_connect("/ws/topics/countdown"),
        lab.http.websocket_connect("/ws/topics/countdown"),
    ):
        with lab.http.websocket_connect("/ws/topics/countdown") as third:
            code, reason = close_within(third)
        assert code == CloseCode.TRY_AGAIN_LATER
        assert "at most 2 echo sockets" in reason
    with lab.http.websocket_connect("/ws/topics/countdown") as again:  # a slot is free again
        again.close()


def test_limits_refused_and_closed_echo_sockets_leave_no_node_or_logger(rocket_lab: LabClient) -> None:
    nodes_before = _node_names(rocket_lab)
    loggers_before = set(logging.root.manager.loggerDict)
    for i in range(60):
        # A type that conflicts with the topic's (this used to leave a node per refusal) ...
        with rocket_lab.http.websocket_connect("/ws/topics/countdown?type=std_msgs/msg/Bool") as ws:
            code, _ = close_within(ws)
            assert code == CloseCode.TYPE_CONFLICT
        # ... and a socket that works, then closes.
        with rocket_lab.http.websocket_connect(f"/ws/topics/countdown?queue_length={1 + i}") as ws:
            ws.close()
    rocket_lab.http.get("/api/health")  # let the last socket's handler finish its clean-up
    assert _node_names(rocket_lab) == nodes_before
    grown = set(logging.root.manager.loggerDict) - loggers_before
    assert len(grown) <= 1, f"one reused echo node name at most, got {sorted(grown)[:5]}"
