from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass
class QoSProfile:
    """Only the keep-last depth matters on this bus."""

    depth: int = 10

    def __init__(self, depth: int = 10, **_ignored: Any) -> None:
        self.depth = depth


qos_profile_sensor_data = QoSProfile(depth=5)
qos_profile_system_default = QoSProfile(depth=10)
