"""roslibpy 2.x (the real package, Twisted transport) against the live lab: the handout's rocket
through rosbridge, at the app's /rosbridge and on rosbridge's own port."""

from __future__ import annotations

import logging
import queue
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest
import roslibpy

from .conftest import RosbridgeServer

WAIT_S = 15.0


class Seen:
    """What the client's callbacks saw, read with a deadline."""

    def __init__(self) -> None:
        self.items: queue.Queue[tuple[Any, ...]] = queue.Queue()

    def put(self, *item: Any) -> None:
        self.items.put(item)

    def wait_for(self, match: Callable[[tuple[Any, ...]], bool], what: str) -> tuple[Any, ...]:
        deadline = time.monotonic() + WAIT_S
        while True:
            try:
                item = self.items.get(timeout=max(0.0, deadline - time.monotonic()))
            except queue.Empty:
                pytest.fail(f"gave up after {WAIT_S} s waiting for {what}")
            if match(item):
                return item

    def clear(self) -> None:
        while not self.items.empty():
            self.items.get_nowait()


class Complaints(logging.Handler):
    """roslibpy logs (and otherwise swallows) what it cannot handle: an unknown op, a binary frame."""

    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.records: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record.getMessage() + (f" {record.exc_info[1]!r}" if record.exc_info else ""))


@pytest.fixture
def complaints() -> Iterator[Complaints]:
    handler = Complaints()
    logger = logging.getLogger("roslibpy")
    logger.addHandler(handler)
    yield handler
    logger.removeHandler(handler)


@pytest.mark.parametrize("way", ["app", "port"])
def test_roslibpy_countdown_abort_topics_and_reset(
    rosbridge_server: RosbridgeServer, complaints: Complaints, way: str
) -> None:
    rosbridge_server.reset_rocket()
    ros = roslibpy.Ros(host=rosbridge_server.urls[way])
    ros.run(timeout=WAIT_S)
    seen = Seen()
    try:
        roslibpy.Topic(ros, "/countdown", "std_msgs/Int64").subscribe(
            lambda m: seen.put("countdown", m["data"])
        )
        roslibpy.Topic(ros, "rosout", "rcl_interfaces/msg/Log").subscribe(
            lambda m: seen.put("log", m["name"], m["msg"])
        )
        seen.wait_for(lambda i: i[0] == "countdown" and i[1] > 0, "the countdown")

        roslibpy.Topic(ros, "abort_takeoff", "std_msgs/Bool").publish(roslibpy.Message({"data": True}))
        seen.wait_for(
            lambda i: i == ("log", "MainControllerNode", "Abort Abort Abort!!!"), "the rocket to abort"
        )

        topics = ros.get_topics()
        assert {"/countdown", "/abort_takeoff", "/keydown"} <= set(topics)
        assert ros.get_topic_type("countdown") == "std_msgs/msg/Int64"
        assert "/MainControllerNode" in ros.get_nodes()

        seen.clear()
        reset = roslibpy.Service(ros, "/rocket/reset", "std_srvs/srv/Trigger")
        response = reset.call(roslibpy.ServiceRequest(), timeout=WAIT_S)
        assert response["success"] is True and response["message"] == "rocket back on the pad"
        seen.wait_for(lambda i: i == ("countdown", 10), "a new countdown from 10 after the reset")
    finally:
        ros.close()
    assert complaints.records == []


def test_roslibpy_call_to_an_absent_service_fails_cleanly(
    rosbridge_server: RosbridgeServer, complaints: Complaints
) -> None:
    ros = roslibpy.Ros(host=rosbridge_server.urls["app"])
    ros.run(timeout=WAIT_S)
    try:
        with pytest.raises(Exception, match="does not exist"):
            roslibpy.Service(ros, "/no_such_service", "std_srvs/srv/Trigger").call(
                roslibpy.ServiceRequest(), timeout=WAIT_S
            )
        assert ros.get_topic_type("/countdown") == "std_msgs/msg/Int64"  # still connected
    finally:
        ros.close()
    assert complaints.records == []
