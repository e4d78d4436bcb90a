"""Publish at a rate, like rqt's Message Publisher: periodic publishers the API starts and stops."""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

from node_runtime.bus import Publisher, Timer
from node_runtime.limits import LimitExceededError
from node_runtime.msgs import Message

MIN_RATE_HZ = 0.01  # one message every 100 s; slower is a mistake (and a timer period of years)
MAX_RATE_HZ = 1000.0


class PublisherError(ValueError):
    """A periodic publisher cannot be started or changed as asked (its rate, for instance)."""


class UnknownPublisherError(LookupError):
    def __init__(self, publisher_id: str) -> None:
        self.publisher_id = publisher_id
        super().__init__(f"no periodic publisher with id {publisher_id!r}")


@dataclass
class RatePublisher:
    id: str
    topic: str
    message: Message
    rate_hz: float
    publisher: Publisher
    timer: Timer | None = None
    enabled: bool = True
    count: int = 0

    def fire(self) -> None:
        self.publisher.publish(self.message)
        self.count += 1

    def describe(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "topic": self.topic,
            "type": self.message.TYPE,
            "msg": self.message.to_dict(),
            "rate_hz": self.rate_hz,
            "enabled": self.enabled,
            "count": self.count,
        }


def check_rate(rate_hz: float) -> float:
    ok = not isinstance(rate_hz, bool) and isinstance(rate_hz, (int, float))
    if not (ok and MIN_RATE_HZ <= rate_hz <= MAX_RATE_HZ):  # NaN fails the comparison too
        raise PublisherError(f"rate_hz must be in {MIN_RATE_HZ:g}..{MAX_RATE_HZ:g} Hz, got {rate_hz!r}")
    return float(rate_hz)


class PublisherManager:
    """Owns the periodic publishers; each is a timer on the API's hidden node."""

    def __init__(self, lab: Any, max_publishers: int = 64) -> None:
        self.lab = lab
        self.max_publishers = max_publishers
        self.items: dict[str, RatePublisher] = {}
        self._ids = itertools.count(1)

    def start(
        self, topic: str, msg: dict[str, Any], type_name: str | None, rate_hz: float, enabled: bool = True
    ) -> RatePublisher:
        """Check everything, then start: a refused request leaves nothing running."""
        rate = check_rate(rate_hz)
        if len(self.items) >= self.max_publishers:
            raise LimitExceededError("periodic publishers", self.max_publishers)
        name, message = self.lab.prepare(topic, msg, type_name)
        pub = self.lab.api_node.publisher_for(name, type(message))
        item = RatePublisher(f"pub{next(self._ids)}", name, message, rate, pub, enabled=enabled)
        if enabled:
            self._arm(item)
        self.items[item.id] = item
        return item

    def _arm(self, item: RatePublisher) -> None:
        item.timer = self.lab.api_node.create_timer(1.0 / item.rate_hz, item.fire)
        item.fire()  # at once, then every period

    def _disarm(self, item: RatePublisher) -> None:
        if item.timer is not None:
            self.lab.api_node.destroy_timer(item.timer)
            item.timer = None

    def get(self, publisher_id: str) -> RatePublisher:
        try:
            return self.items[publisher_id]
        except KeyError:
            raise UnknownPublisherError(publisher_id) from None

    def update(
        self,
        publisher_id: str,
        *,
        enabled: bool | None = None,
        rate_hz: float | None = None,
        msg: dict[str, Any] | None = None,
    ) -> RatePublisher:
        """Change a running publisher; everything is checked before anything changes."""
        item = self.get(publisher_id)
        rate = check_rate(rate_hz) if rate_hz is not None else item.rate_hz
        message = self.lab.prepare(item.topic, msg, item.message.TYPE)[1] if msg is not None else item.message
        self._disarm(item)
        item.rate_hz, item.message = rate, message
        item.enabled = item.enabled if enabled is None else enabled
        if item.enabled:
            self._arm(item)
        return item

    def stop(self, publisher_id: str) -> RatePublisher:
        item = self.get(publisher_id)
        self._disarm(item)
        del self.items[publisher_id]
        return item

    def stop_all(self) -> None:
        for publisher_id in list(self.items):
            self.stop(publisher_id)
