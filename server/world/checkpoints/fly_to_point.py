"""Checkpoint 2: positions published at 1 Hz fly the drone to (5, 5, 10).

Met when one publisher's last RATE_MESSAGES setpoints at the target came at RATE_HZ (the panel, the
CLI or REST alike), the newest within STALE_S, and the drone's GPS has stayed within NEAR_M of the
target for HOLD_S. It is met once per stay at the target: a drone that keeps hovering there while
the publisher goes on publishing is the same success, not a new one every HOLD_S.
"""

from __future__ import annotations

import math
from collections import OrderedDict, deque

from server.world.checkpoints.declared import Checkpoint, Evidence, Step
from server.world.checkpoints.events import Event, Gps, Setpoint
from server.world.checkpoints.page_names import (
    CODE,
    ENABLED,
    NEW_FILE,
    POSITION_TEMPLATE,
    PUBLISHER,
    RATE,
    RUN,
)
from server.world.checkpoints.timeline import Timeline, Track

TARGET = (5.0, 5.0, 10.0)
AT_TARGET_M = 0.05  # a setpoint this close to the target is one "to" it
RATE_HZ = (0.8, 1.2)
RATE_MESSAGES = 5
STALE_S = 2.5  # the publisher's newest setpoint no older than this: it still publishes
NEAR_M = 0.3
HOLD_S = 3.0
MAX_PUBLISHERS = 16  # the publishers whose times are kept (the newest)


def _distance(a: tuple[float, float, float], b: tuple[float, float, float]) -> float:
    return math.dist(a, b)


class FlyToPointCheck:
    def __init__(self) -> None:
        self.setpoints = Timeline(60)
        self.track = Track()
        self._times: OrderedDict[str, deque[float]] = OrderedDict()  # per publisher, at the target
        self._near_since: float | None = None
        self._held = False  # met during this stay near the target
        self._distance_m: float | None = None
        self._last_s = 0.0
        self.started = False

    def _rate(self, now_s: float) -> tuple[str, float] | None:
        """The publisher (and its rate) whose last setpoints to the target came at RATE_HZ."""
        best: tuple[str, float] | None = None
        for who, times in self._times.items():
            if len(times) < RATE_MESSAGES or now_s - times[-1] > STALE_S or times[-1] == times[0]:
                continue
            rate = (len(times) - 1) / (times[-1] - times[0])
            if RATE_HZ[0] <= rate <= RATE_HZ[1]:
                best = (who, rate)
        return best

    def _latest_rate(self) -> tuple[int, float | None]:
        if not self._times:
            return 0, None
        times = next(reversed(self._times.values()))
        if len(times) < 2 or times[-1] == times[0]:
            return len(times), None
        return len(times), (len(times) - 1) / (times[-1] - times[0])

    def feed(self, event: Event) -> Evidence | None:
        if isinstance(event, Setpoint):
            self.started = True
            self.setpoints.add(event.t_s, "setpoint", [round(v, 3) for v in event.xyz], event.source)
            who = event.source.node or event.source.process
            if _distance(event.xyz, TARGET) <= AT_TARGET_M:
                times = self._times.pop(who, None) or deque(maxlen=RATE_MESSAGES)
                times.append(event.t_s)
                self._times[who] = times  # the newest publisher last
                while len(self._times) > MAX_PUBLISHERS:
                    self._times.popitem(last=False)
            else:
                self._times.pop(who, None)  # elsewhere: its run of setpoints to the target ends
        elif isinstance(event, Gps):
            self.track.add(event.t_s, event.xyz)
            self._distance_m = _distance(event.xyz, TARGET)
            if self._distance_m <= NEAR_M:
                if self._near_since is None:
                    self._near_since = event.t_s
            else:
                self._near_since = None
                self._held = False
        return self.tick(event.t_s)

    def tick(self, now_s: float) -> Evidence | None:
        self._last_s = now_s
        near = self._near_since
        if near is None or self._held or now_s - near < HOLD_S:
            return None
        rate = self._rate(now_s)
        if rate is None:
            return None
        self._held = True  # met: it may be met again after the drone has left and come back
        return {
            "target": list(TARGET),
            "publisher": rate[0],
            "rate_hz": round(rate[1], 3),
            "held_s": round(now_s - near, 2),
            "setpoints": self.setpoints.entries(),
            "track": self.track.since(now_s - 120.0),
        }

    def progress(self, now_s: float) -> str:
        if self._held:
            return "done: the drone held (5, 5, 10) for 3 s"
        count, rate = self._latest_rate()
        where = "" if self._distance_m is None else f"; {self._distance_m:.1f} m from (5, 5, 10)"
        if count == 0:
            return "publish (5, 5, 10) on /uav/input/position once a second" + where
        at = f" at {rate:.1f} Hz" if rate is not None else ""
        return f"{count} positions to (5, 5, 10){at}{where}"


CHECKPOINT = Checkpoint(
    name="fly_to_point",
    title="Fly the drone to (5, 5, 10) with positions at 1 Hz",
    steps=(
        Step(
            "Start the drone's launch.",
            ("ros2lab launch flightcontroller fly.launch",),
            running=("/position_controller_node",),
            already="The drone is already flying (the lab's launch started it): it hovers at (0, 0, 3).",
        ),
        Step(
            "Publish geometry_msgs/Vector3 (5, 5, 10) on /uav/input/position once a second.",
            ('ros2lab topic pub -r 1 /uav/input/position geometry_msgs/msg/Vector3 "{x: 5, y: 5, z: 10}"',),
            page=(
                f"In the {PUBLISHER} panel: topic /uav/input/position, x 5, y 5, z 10, {RATE} 1, "
                f"then tick {ENABLED}. Or in the {CODE} view: {NEW_FILE}, Start from "
                f"\u201c{POSITION_TEMPLATE}\u201d, fill in its TODOs and press {RUN}."
            ),
        ),
        Step("Keep publishing until the drone has held (5, 5, 10) for 3 s.", ()),
    ),
    check=FlyToPointCheck,
)
