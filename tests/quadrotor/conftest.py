"""The quadrotor lab as launched, on a manual clock: a Lab stepped by hand and a probe that records topics.

Nothing here sleeps: ``lab.executor.spin_until(t)`` moves the clock to each timer's deadline in turn.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from node_runtime.bus import ManualClock, Node
from node_runtime.msgs import Float64, Message, PoseStamped, TwistStamped, Vector3
from server.host.settings import LabSettings, Settings
from server.world.lab import Lab

DATA = Path(__file__).resolve().parent / "data"
FLY_NO_NOISE = str(DATA / "fly_no_noise.launch")
GROUNDED_SENSORS = str(DATA / "grounded_sensors.launch")

SENSOR_TOPICS: dict[str, type[Message]] = {
    "/uav/sensors/gps": PoseStamped,
    "/uav/sensors/velocity": TwistStamped,
    "/uav/sensors/attitude": Vector3,
    "/uav/sensors/pressure": Float64,
    "/uav/input/position": Vector3,
    "/uav/input/velocity": Vector3,
}


class Probe:
    """A node that keeps ``(time_s, msg)`` for every message on the topics it is given, as rqt would."""

    def __init__(self, lab: Lab, topics: dict[str, type[Message]], name: str = "probe") -> None:
        self.lab = lab
        with lab.bus.activate():
            self.node = Node(name)
        self.got: dict[str, list[tuple[float, Any]]] = {}
        for topic, msg_type in topics.items():
            self.got[topic] = []
            self.node.create_subscription(msg_type, topic, self._recorder(topic), 10_000)

    def _recorder(self, topic: str) -> Callable[[Message], None]:
        def record(msg: Message) -> None:
            self.got[topic].append((self.lab.bus.clock.now(), msg))

        return record

    def times(self, topic: str, after_s: float = -np.inf, until_s: float = np.inf) -> np.ndarray:
        return np.array([t for t, _ in self.got[topic] if after_s <= t <= until_s])

    def positions(self, after_s: float = -np.inf, until_s: float = np.inf) -> np.ndarray:
        """GPS samples as rows (t_s, x_m, y_m, z_m)."""
        rows = [
            (t, m.pose.position.x, m.pose.position.y, m.pose.position.z)
            for t, m in self.got["/uav/sensors/gps"]
            if after_s <= t <= until_s
        ]
        return np.array(rows).reshape(-1, 4)

    def velocities(self, after_s: float = -np.inf, until_s: float = np.inf) -> np.ndarray:
        """Velocity samples as rows (t_s, vx, vy, vz) in m/s, world frame."""
        rows = [
            (t, m.twist.linear.x, m.twist.linear.y, m.twist.linear.z)
            for t, m in self.got["/uav/sensors/velocity"]
            if after_s <= t <= until_s
        ]
        return np.array(rows).reshape(-1, 4)

    def vectors(self, topic: str, after_s: float = -np.inf) -> list[tuple[float, float, float]]:
        return [(m.x, m.y, m.z) for t, m in self.got[topic] if t >= after_s]


def make_lab(launch: str = "fly", **launch_args: str) -> Lab:
    """A Lab on a manual clock at t = 0 with no display; nodes are launched by ``start``."""
    return Lab(
        Settings(lab=LabSettings(launch=launch, viewer=False, launch_args=launch_args)), ManualClock(0.0)
    )


def start(lab: Lab, topics: dict[str, type[Message]] | None = None) -> Probe:
    """Make the probe first (so it sees the first messages), then launch the nodes."""
    probe = Probe(lab, topics or SENSOR_TOPICS)
    lab.start_nodes()
    return probe


def node(lab: Lab, name: str) -> Any:
    return lab.bus.get_node(name)


class Flight:
    """One run of the default fly launch: take off and hover for 15 s, then a step to (5, 5, 10) for 15 s."""

    STEP_AT_S = 15.0
    END_S = 30.0
    TARGET_M = (5.0, 5.0, 10.0)

    def __init__(self, launch: str = "fly") -> None:
        self.lab = make_lab(launch)
        self.probe = start(self.lab)
        self.lab.executor.spin_until(self.STEP_AT_S)
        self.lab.publish("/uav/input/position", dict(zip("xyz", self.TARGET_M, strict=True)), None)
        self.lab.executor.spin_until(self.END_S)


@pytest.fixture(scope="session")
def fly_flight() -> Iterator[Flight]:
    """The default launch (process noise on), flown once per test session; tests only read it."""
    flight = Flight()
    yield flight
    flight.lab.launcher.shutdown()


@pytest.fixture(scope="session")
def quiet_flight() -> Iterator[Flight]:
    """The same flight with the dynamics node's noise off (a launch file sets its ``noise`` param)."""
    flight = Flight(FLY_NO_NOISE)
    yield flight
    flight.lab.launcher.shutdown()
