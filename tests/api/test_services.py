"""REST services through the real app: ``GET /api/services`` and ``POST /api/services/{name}``, as
``ros2 service list`` and ``ros2 service call`` (the rocket's reset is a std_srvs/srv/Trigger)."""

from __future__ import annotations

from typing import Any

from labclient import LabClient

from node_runtime.bus import Node
from node_runtime.msgs import get_service_type


def lab_of(client: LabClient) -> Any:
    return client.http.app.state.lab  # type: ignore[attr-defined]


def on_loop(client: LabClient, fn: Any) -> Any:
    """Run ``fn`` on the app's event-loop thread, where the executor touches the bus."""
    assert client.http.portal is not None
    return client.http.portal.call(fn)


def test_the_rocket_reset_service_is_listed_with_its_type_and_server(rocket_lab: LabClient) -> None:
    services = rocket_lab.http.get("/api/services").json()
    reset = next(s for s in services if s["name"] == "/rocket/reset")
    assert reset["type"] == "std_srvs/srv/Trigger"
    assert reset["servers"] == ["/_rest_api"]


def test_calling_the_reset_service_restarts_the_countdown(counting_lab: LabClient) -> None:
    counting_lab.wait_latest("/countdown", lambda msg: msg["data"] <= 9, "the countdown to move")
    r = counting_lab.http.post("/api/services/rocket/reset", json={})
    assert r.status_code == 200, r.text
    assert r.json() == {
        "service": "/rocket/reset",
        "type": "std_srvs/srv/Trigger",
        "response": {"success": True, "message": r.json()["response"]["message"]},
    }
    counting_lab.wait_latest("/countdown", lambda msg: msg["data"] == 10, "the countdown to restart at 10")


def test_a_service_nobody_serves_is_404_even_with_a_type(rocket_lab: LabClient) -> None:
    for body in ({}, {"type": "std_srvs/srv/Trigger"}, {"type": "std_srvs/srv/Empty"}):
        r = rocket_lab.http.post("/api/services/no/such/service", json=body)
        assert r.status_code == 404, (body, r.text)
        assert "/no/such/service" in r.json()["detail"]
    names = {s["name"] for s in rocket_lab.http.get("/api/services").json()}
    assert "/no/such/service" not in names  # the refused calls left no client behind


def test_a_wrong_type_or_a_bad_request_field_is_refused_and_calls_nothing(counting_lab: LabClient) -> None:
    lab = lab_of(counting_lab)
    calls_before = lab.bus.services["/rocket/reset"].calls
    r = counting_lab.http.post("/api/services/rocket/reset", json={"type": "std_srvs/srv/SetBool"})
    assert r.status_code == 409 and "std_srvs/srv/Trigger" in r.json()["detail"]
    r = counting_lab.http.post("/api/services/rocket/reset", json={"request": {"data": True}})
    assert r.status_code == 422 and "data" in str(r.json()["detail"])
    r = counting_lab.http.post("/api/services/rocket/reset", json={"timeout_s": 0})
    assert r.status_code == 422
    r = counting_lab.http.post("/api/services/rocket/reset", json={"timeout_s": "5"})
    assert r.status_code == 422 and "timeout_s" in str(r.json()["detail"])
    assert lab.bus.services["/rocket/reset"].calls == calls_before


def test_a_server_that_never_answers_is_a_504_naming_the_service(rocket_lab: LabClient) -> None:
    trigger = get_service_type("std_srvs/srv/Trigger")

    def start_broken() -> Node:
        with lab_of(rocket_lab).bus.activate():
            node = Node("Broken")

        def answer(_request: Any, _response: Any) -> Any:
            raise RuntimeError("the answer was lost")

        node.create_service(trigger, "/broken/trigger", answer)
        return node

    on_loop(rocket_lab, start_broken)
    r = rocket_lab.http.post("/api/services/broken/trigger", json={"timeout_s": 0.3})
    assert r.status_code == 504, r.text
    assert "/broken/trigger" in r.json()["detail"]
    assert rocket_lab.healthy()
