"""/api/health and /api/rocket/reset through the real app, the rocket launch running."""

from __future__ import annotations

from collections.abc import Callable

from labclient import LabClient, wait_until


def test_health_rocket_lab_running_reports_ok_with_its_graph(rocket_lab: LabClient) -> None:
    response = rocket_lab.http.get("/api/health")

    assert response.status_code == 200
    health = response.json()
    assert health["status"] == "ok"
    assert health["launch"] == "rocket"
    assert (
        health["nodes"] >= 5
    )  # CountDownNode, MainControllerNode, RocketEngineNode, keyboard, KeyboardManager
    assert health["topics"] >= 6
    assert health["uptime_s"] >= 0


def test_reset_rocket_mid_countdown_counts_down_from_10_again(counting_lab: LabClient) -> None:
    counting_lab.wait_latest("/countdown", lambda m: m["data"] <= 8, "counted down to 8")
    count_before = counting_lab.publish_count("/countdown")

    response = counting_lab.http.post("/api/rocket/reset")

    assert response.status_code == 200
    assert response.json() == {"status": "reset"}

    def restarted() -> bool:
        countdown = counting_lab.topic("/countdown")
        return countdown["publish_count"] > count_before and countdown["latest"] == {"data": 10}

    wait_until(restarted, "/countdown back at 10 after the reset")
    counting_lab.wait_latest("/countdown", lambda m: m["data"] == 9, "counting on after the reset")


def _graph(lab: LabClient) -> dict[str, tuple[str, set[str], set[str]]]:
    """Topic → (type, publishers, subscribers); restarted nodes may come back in another order."""
    return {
        t["name"]: (t["type"], set(t["publishers"]), set(t["subscribers"]))
        for t in lab.http.get("/api/topics").json()
    }


def test_reset_rocket_keeps_the_rocket_graph(make_lab: Callable[..., LabClient]) -> None:
    lab = make_lab()
    graph_before = _graph(lab)

    assert lab.http.post("/api/rocket/reset").status_code == 200

    assert _graph(lab) == graph_before
    assert lab.healthy()
