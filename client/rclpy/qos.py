"""rclpy's QoS: policies, profiles and the preset profiles, with rclpy's names.

A profile's depth sets a subscription's keep-last queue and, with its reliability and
durability, the QoS field of the endpoint's token on the wire, as rmw_zenoh writes it.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum, IntEnum
from typing import Any

from rclpy.duration import Duration

DEPTH_SYSTEM_DEFAULT = 0
RMW_ZENOH_DEFAULT_DEPTH = 42  # what rmw_zenoh keeps when a profile leaves the depth to the system


class ReliabilityPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class DurabilityPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2
    UNKNOWN = 3
    BEST_AVAILABLE = 4


class HistoryPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2
    UNKNOWN = 3


class LivelinessPolicy(IntEnum):
    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_TOPIC = 3
    UNKNOWN = 4
    BEST_AVAILABLE = 5


QoSReliabilityPolicy = ReliabilityPolicy
QoSDurabilityPolicy = DurabilityPolicy
QoSHistoryPolicy = HistoryPolicy
QoSLivelinessPolicy = LivelinessPolicy

_POLICIES: dict[str, type[IntEnum]] = {
    "history": HistoryPolicy,
    "reliability": ReliabilityPolicy,
    "durability": DurabilityPolicy,
    "liveliness": LivelinessPolicy,
}
_DURATIONS = ("deadline", "lifespan", "liveliness_lease_duration")


class QoSPolicyKind(IntEnum):
    """Which policy an incompatible-QoS event names, and which a QoS override sets (rmw's bits)."""

    INVALID = 1 << 0
    DURABILITY = 1 << 1
    DEADLINE = 1 << 2
    LIVELINESS = 1 << 3
    RELIABILITY = 1 << 4
    HISTORY = 1 << 5
    LIFESPAN = 1 << 6
    DEPTH = 1 << 7
    LIVELINESS_LEASE_DURATION = 1 << 8
    AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9


def qos_policy_name_from_kind(policy_kind: QoSPolicyKind | int) -> str:
    return QoSPolicyKind(policy_kind).name


class InvalidQoSProfileException(Exception):
    """A profile that cannot be (KEEP_LAST without a depth, an unknown policy)."""


class QoSProfile:
    """rclpy's keyword-only profile: ``QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)``."""

    def __init__(self, **kwargs: Any) -> None:
        unknown = set(kwargs) - {"depth", *_POLICIES, *_DURATIONS, "avoid_ros_namespace_conventions"}
        if unknown:
            raise InvalidQoSProfileException(f"QoSProfile has no field {sorted(unknown)[0]!r}")
        if "history" not in kwargs and "depth" not in kwargs:
            raise InvalidQoSProfileException("QoSProfile needs a history or a depth")
        self.history = HistoryPolicy(kwargs.get("history", HistoryPolicy.KEEP_LAST))
        self.depth = int(kwargs.get("depth", DEPTH_SYSTEM_DEFAULT))
        if self.history == HistoryPolicy.KEEP_LAST and self.depth < 1 and "depth" in kwargs:
            raise InvalidQoSProfileException("a KEEP_LAST profile needs a depth of at least 1")
        self.reliability = ReliabilityPolicy(kwargs.get("reliability", ReliabilityPolicy.RELIABLE))
        self.durability = DurabilityPolicy(kwargs.get("durability", DurabilityPolicy.VOLATILE))
        self.liveliness = LivelinessPolicy(kwargs.get("liveliness", LivelinessPolicy.SYSTEM_DEFAULT))
        self.deadline: Duration = kwargs.get("deadline", Duration())
        self.lifespan: Duration = kwargs.get("lifespan", Duration())
        self.liveliness_lease_duration: Duration = kwargs.get("liveliness_lease_duration", Duration())
        self.avoid_ros_namespace_conventions = bool(kwargs.get("avoid_ros_namespace_conventions", False))

    def _fields(self) -> tuple[object, ...]:
        return (
            self.history,
            self.depth,
            self.reliability,
            self.durability,
            self.liveliness,
            self.deadline,
            self.lifespan,
            self.liveliness_lease_duration,
        )

    def __eq__(self, other: object) -> bool:
        return isinstance(other, QoSProfile) and self._fields() == other._fields()

    def __hash__(self) -> int:
        return hash(self._fields())

    def __repr__(self) -> str:
        return (
            f"QoSProfile(history={self.history.name}, depth={self.depth}, "
            f"reliability={self.reliability.name}, durability={self.durability.name})"
        )


def keep_depth(qos: QoSProfile | int) -> int:
    """The keep-last depth a profile (or rclpy's plain int) asks for; KEEP_ALL and the system's
    default get rmw_zenoh's default depth."""
    if isinstance(qos, int):
        return qos
    if qos.history == HistoryPolicy.KEEP_ALL or qos.depth < 1:
        return RMW_ZENOH_DEFAULT_DEPTH
    return qos.depth


@dataclass(frozen=True)
class WireQoS:
    """What the bus and the Zenoh transport take from a profile: rmw's enum values (0: the system's
    default, 1: reliable / transient local, 2: best effort / volatile)."""

    depth: int
    reliability: int
    durability: int


qos_profile_sensor_data = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
qos_profile_system_default = QoSProfile(
    history=HistoryPolicy.SYSTEM_DEFAULT,
    reliability=ReliabilityPolicy.SYSTEM_DEFAULT,
    durability=DurabilityPolicy.SYSTEM_DEFAULT,
)
qos_profile_services_default = QoSProfile(depth=10)
qos_profile_parameters = QoSProfile(depth=1000)
qos_profile_parameter_events = QoSProfile(depth=1000)
qos_profile_action_status_default = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
qos_profile_rosout_default = QoSProfile(
    depth=1000, durability=DurabilityPolicy.TRANSIENT_LOCAL, lifespan=Duration(seconds=10)
)


class QoSPresetProfiles(Enum):
    """rclpy's presets by name: ``QoSPresetProfiles.SENSOR_DATA.value``, ``get_from_short_key``."""

    UNKNOWN = QoSProfile(depth=DEPTH_SYSTEM_DEFAULT, history=HistoryPolicy.UNKNOWN)
    SYSTEM_DEFAULT = qos_profile_system_default
    SENSOR_DATA = qos_profile_sensor_data
    SERVICES_DEFAULT = qos_profile_services_default
    PARAMETERS = qos_profile_parameters
    PARAMETER_EVENTS = qos_profile_parameter_events
    ACTION_STATUS_DEFAULT = qos_profile_action_status_default
    ROSOUT_DEFAULT = qos_profile_rosout_default

    @classmethod
    def short_keys(cls) -> list[str]:
        return [m.name.lower() for m in cls]

    @classmethod
    def get_from_short_key(cls, name: str) -> QoSProfile:
        return cls[name.upper()].value


__all__ = [
    "DurabilityPolicy",
    "HistoryPolicy",
    "InvalidQoSProfileException",
    "LivelinessPolicy",
    "QoSDurabilityPolicy",
    "QoSHistoryPolicy",
    "QoSLivelinessPolicy",
    "QoSPolicyKind",
    "QoSPresetProfiles",
    "QoSProfile",
    "QoSReliabilityPolicy",
    "ReliabilityPolicy",
    "qos_policy_name_from_kind",
    "qos_profile_action_status_default",
    "qos_profile_parameter_events",
    "qos_profile_parameters",
    "qos_profile_rosout_default",
    "qos_profile_sensor_data",
    "qos_profile_services_default",
    "qos_profile_system_default",
]
