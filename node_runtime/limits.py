"""What a client may ask of one app: how many of each thing it may create, and which values it may
publish on the topics that reach a simulator or a view.

Both kinds of refusal are errors of their own, so the API maps them to a status once
(``LimitExceededError`` → 429, ``ValueLimitError`` → 422) and no other ``ValueError`` is
mistaken for a client's mistake.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from node_runtime.bus.clock import Clock
from node_runtime.msgs import Message


class RateLimit:
    """A token bucket on the lab's clock: ``rate_hz`` calls a second, bursts of ``burst``."""

    def __init__(self, clock: Clock, rate_hz: float, burst: int) -> None:
        self.clock, self.rate_hz, self.burst = clock, rate_hz, float(burst)
        self._tokens = float(burst)
        self._at = clock.now()
        self.refused = 0

    def take(self) -> bool:
        self._tokens, self._at = self._level(), self.clock.now()
        if self._tokens >= 1.0:
            self._tokens -= 1.0
            return True
        self.refused += 1
        return False

    def ready(self) -> bool:
        """Whether ``take`` would succeed now, without taking."""
        return self._level() >= 1.0

    def retry_after_s(self) -> float:
        """Seconds until one call is allowed again (0 when one is now)."""
        return max(0.0, (1.0 - self._level()) / self.rate_hz) if self.rate_hz > 0 else math.inf

    def _level(self) -> float:
        return min(self.burst, self._tokens + (self.clock.now() - self._at) * self.rate_hz)


def per_second(clock: Clock, rate_hz: float | None) -> RateLimit | None:
    """``rate_hz`` a second in bursts of a second's worth; None (no limit) for None."""
    return None if rate_hz is None else RateLimit(clock, rate_hz, max(1, math.ceil(rate_hz)))


class KeyedRateLimit:
    """A ``RateLimit`` per key (a client's address), at most ``max_keys`` of them: the oldest key
    is forgotten first, so a stream of new keys cannot grow memory."""

    def __init__(self, clock: Clock, rate_hz: float, burst: int, max_keys: int = 4096) -> None:
        self.clock, self.rate_hz, self.burst, self.max_keys = clock, rate_hz, burst, max_keys
        self._limits: OrderedDict[str, RateLimit] = OrderedDict()

    def __len__(self) -> int:
        return len(self._limits)

    def __getitem__(self, key: str) -> RateLimit:
        limit = self._limits.get(key)
        if limit is None:
            limit = self._limits[key] = RateLimit(self.clock, self.rate_hz, self.burst)
            while len(self._limits) > self.max_keys:
                self._limits.popitem(last=False)
        else:
            self._limits.move_to_end(key)
        return limit


class LimitExceededError(Exception):
    """One more of something the app allows only so many of (publishers, launches, sockets)."""

    def __init__(self, what: str, limit: int) -> None:
        self.what, self.limit = what, limit
        super().__init__(f"at most {limit} {what} at once; stop one first")


class ValueLimitError(ValueError):
    """A field value outside what a simulator or a view can take."""


@dataclass(frozen=True)
class FieldLimit:
    """``low <= value <= high`` for the field at ``path`` (dotted), in ``unit``."""

    path: str
    low: float
    high: float
    unit: str


def _each(paths: str, low: float, high: float, unit: str) -> tuple[FieldLimit, ...]:
    return tuple(FieldLimit(path, low, high, unit) for path in paths.split())


POSITION_M = 1e4  # beyond this a position is a mistake, not a far-away goal (the arena is 20 m)
SPEED_M_S = 1e4  # faster than any rocket or drone in the lab
ANGLE_RAD = 10.0  # a few turns; attitudes are within ±π
BODY_RATE_RAD_S = 100.0
THRUST_N = 1e3  # the lab's drone weighs 1 kg; its motors give about 4 g
XYZ = "x y z"

# topic → (type, limits). Only the REST API's messages are checked here: nodes check their own.
TOPIC_LIMITS: Mapping[str, tuple[str, tuple[FieldLimit, ...]]] = MappingProxyType(
    {
        "/uav/input/position": ("geometry_msgs/msg/Vector3", _each(XYZ, -POSITION_M, POSITION_M, "m")),
        "/uav/input/velocity": ("geometry_msgs/msg/Vector3", _each(XYZ, -SPEED_M_S, SPEED_M_S, "m/s")),
        "/uav/input/attitude": ("geometry_msgs/msg/Vector3", _each(XYZ, -ANGLE_RAD, ANGLE_RAD, "rad")),
        "/uav/input/thrust": ("std_msgs/msg/Float64", _each("data", -THRUST_N, THRUST_N, "N")),
        "/uav/input/rateThrust": (
            "geometry_msgs/msg/TwistStamped",
            _each(
                "twist.angular.x twist.angular.y twist.angular.z", -BODY_RATE_RAD_S, BODY_RATE_RAD_S, "rad/s"
            )
            + _each("twist.linear.x twist.linear.y twist.linear.z", -THRUST_N, THRUST_N, "N"),
        ),
        "/uav/sensors/gps": (
            "geometry_msgs/msg/PoseStamped",
            _each("pose.position.x pose.position.y pose.position.z", -POSITION_M, POSITION_M, "m")
            + _each("pose.orientation.x pose.orientation.y pose.orientation.z pose.orientation.w", -1, 1, ""),
        ),
        "/uav/sensors/velocity": (
            "geometry_msgs/msg/TwistStamped",
            _each("twist.linear.x twist.linear.y twist.linear.z", -SPEED_M_S, SPEED_M_S, "m/s")
            + _each(
                "twist.angular.x twist.angular.y twist.angular.z", -BODY_RATE_RAD_S, BODY_RATE_RAD_S, "rad/s"
            ),
        ),
        "/uav/sensors/attitude": ("geometry_msgs/msg/Vector3", _each(XYZ, -ANGLE_RAD, ANGLE_RAD, "rad")),
        "/uav/sensors/pressure": ("std_msgs/msg/Float64", _each("data", 0.0, 2e5, "Pa")),
        "/cmd_vel": ("std_msgs/msg/Float64", _each("data", -SPEED_M_S, SPEED_M_S, "m/s")),
        "/sensor_vel": ("std_msgs/msg/Float64", _each("data", -SPEED_M_S, SPEED_M_S, "m/s")),
        "/countdown": ("std_msgs/msg/Int64", _each("data", -1e6, 1e6, "s")),
    }
)


def check_finite_json(value: Any, path: str = "msg") -> None:
    """JSON parsed by Python may carry NaN or Infinity (and a GUI may send them); no topic wants them."""
    if isinstance(value, float) and not math.isfinite(value):
        raise ValueLimitError(f"{path}: {value} is not a finite number")
    if isinstance(value, dict):
        for key, item in value.items():
            check_finite_json(item, f"{path}.{key}")
    elif isinstance(value, list):
        for index, item in enumerate(value):
            check_finite_json(item, f"{path}[{index}]")


def _field(message: Message, path: str) -> Any:
    value: Any = message
    for name in path.split("."):
        value = getattr(value, name)
    return value


def check_topic_limits(topic: str, message: Message) -> None:
    """Raise ``ValueLimitError`` if a field of a message for ``topic`` is out of its range."""
    entry = TOPIC_LIMITS.get(topic)
    if entry is None or entry[0] != message.TYPE:
        return
    for limit in entry[1]:
        value = float(_field(message, limit.path))
        if not (math.isfinite(value) and limit.low <= value <= limit.high):
            unit = f" {limit.unit}" if limit.unit else ""
            raise ValueLimitError(
                f"{topic}: msg.{limit.path} = {value:g} is out of range {limit.low:g}..{limit.high:g}{unit}"
            )
