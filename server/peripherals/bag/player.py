"""``ros2 bag play``: a node that publishes a bag's messages back onto the bus with their timing.

Messages are read lazily from the MCAP in log-time order, so a long bag costs no memory. Each
is published when ``(log_time - first log_time) / rate`` has passed on the bus clock since play
began: with a ManualClock a test sees the recorded intervals exactly. ``loop`` starts over after
the last message. Topics whose type this lab does not know, or that the bus already carries
with another type, are skipped with a warning.
"""

from __future__ import annotations

import struct
from collections.abc import Generator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mcap.exceptions import McapError
from mcap.reader import make_reader

from node_runtime.bus import Node, Publisher, Timer, TopicTypeError
from node_runtime.msgs import UnknownTypeError, get_type
from node_runtime.msgs.wire import WireError, deserialize
from server.peripherals.bag.errors import BagError
from server.peripherals.bag.writer import MESSAGE_ENCODING, SCHEMA_ENCODING

MIN_RATE, MAX_RATE = 0.01, 100.0
MCAP_MAGIC = b"\x89MCAP0\r\n"
DUE_EPS_S = 1e-6  # a timer's deadline may land a rounding error before the message's time


def mcap_file(path: Path) -> Path:
    """The MCAP file of a bag given as the file itself or as its folder (as ros2 bag takes either)."""
    try:
        return _mcap_file(path)
    except OSError as exc:  # a name too long, a folder not readable: the request's fault, not ours
        raise BagError(f"{str(path)[:200]} cannot be opened: {exc.strerror or exc}") from None


def _mcap_file(path: Path) -> Path:
    if path.is_dir():
        files = sorted(path.glob("*.mcap"))
        if not files:
            raise BagError(f"{path} holds no .mcap file")
        path = files[0]
    if not path.is_file():
        raise BagError(f"no bag at {path}")
    with path.open("rb") as f:
        if f.read(len(MCAP_MAGIC)) != MCAP_MAGIC:
            raise BagError(f"{path} is not an MCAP file")
    return path


@dataclass(frozen=True)
class Recorded:
    topic: str
    type_name: str
    log_time_ns: int
    data: bytes


def read_bag(path: Path) -> Generator[Recorded, None, None]:
    """The bag's CDR messages in log-time order, one at a time."""
    with path.open("rb") as f:
        for schema, channel, message in make_reader(f).iter_messages(log_time_order=True):
            if (
                schema is None
                or schema.encoding != SCHEMA_ENCODING
                or channel.message_encoding != MESSAGE_ENCODING
            ):
                continue
            yield Recorded(channel.topic, schema.name, message.log_time, message.data)


class PlayerNode(Node):
    """Node ``rosbag2_player`` (as ros2 bag names its own); ``finished`` once the bag is done."""

    def __init__(
        self, path: Path, *, rate: float = 1.0, loop: bool = False, node_name: str = "rosbag2_player"
    ) -> None:
        if not MIN_RATE <= rate <= MAX_RATE:
            raise BagError(f"rate must be in {MIN_RATE}..{MAX_RATE}, got {rate}")
        self.path = mcap_file(path)
        super().__init__(node_name)
        self.rate = rate
        self.loop = loop
        self.finished = False
        self.published = 0
        self.skipped: dict[str, str] = {}  # topic → why it is not played
        self._publishers: dict[str, Publisher] = {}
        self._timer: Timer | None = None
        self._messages: Generator[Recorded, None, None] | None = None
        self._next: Recorded | None = None
        self._start_s = 0.0
        self._first_ns = 0
        try:
            self._begin()
        except BagError:
            self.destroy_node()
            raise

    def _advance(self) -> Recorded | None:
        """The next message, or None at the end (or where a damaged file stops making sense)."""
        if self._messages is None:
            return None
        try:
            return next(self._messages, None)
        except (McapError, struct.error, EOFError, OSError) as exc:  # OSError: the file went away
            if self.published == 0:
                raise BagError(f"{self.path} cannot be read: {exc}") from None
            self.get_logger().warning(f"{self.path} ends early: {exc}")
            return None

    def _begin(self) -> None:
        self.close()
        self._messages = read_bag(self.path)
        self._next = self._advance()
        if self._next is None:
            self._finish()
            return
        self._first_ns = self._next.log_time_ns
        self._start_s = self.bus.clock.now()
        self._schedule()

    def _due_s(self, msg: Recorded) -> float:
        return self._start_s + (msg.log_time_ns - self._first_ns) / 1e9 / self.rate

    def _schedule(self) -> None:
        """One-shot timer for the next message (rclpy timers are periodic: each is replaced)."""
        if self._timer is not None:
            self.destroy_timer(self._timer)
            self._timer = None
        # One reading of the clock for the whole pass: on a wall clock, time moves between two
        # readings, and a message found not yet due could be due (delay <= 0) by the second.
        now = self.bus.clock.now()
        while self._next is not None and self._due_s(self._next) <= now + DUE_EPS_S:
            self._publish(self._next)
            self._next = self._advance()
            now = self.bus.clock.now()
        if self._next is None:
            if self.loop and self.published:
                self._begin()
            else:
                self._finish()
            return
        self._timer = self.create_timer(self._due_s(self._next) - now, self._schedule)

    def _publisher(self, msg: Recorded) -> Publisher | None:
        pub = self._publishers.get(msg.topic)
        if pub is not None or msg.topic in self.skipped:
            return pub
        try:
            pub = self.create_publisher(get_type(msg.type_name), msg.topic, 1000)
        except (UnknownTypeError, TopicTypeError) as exc:
            self.skipped[msg.topic] = str(exc)
            self.get_logger().warning(f"not playing {msg.topic}: {exc}")
            return None
        self._publishers[msg.topic] = pub
        return pub

    def _publish(self, msg: Recorded) -> None:
        pub = self._publisher(msg)
        if pub is None:
            return
        try:
            pub.publish(deserialize(msg.type_name, msg.data))
        except WireError as exc:
            self.get_logger().warning(f"skipped a message on {msg.topic}: {exc}")
            return
        self.published += 1

    def _finish(self) -> None:
        self.finished = True
        self._next = None
        self.close()

    def close(self) -> None:
        """Let go of the bag file (the node itself stays until destroyed)."""
        if self._messages is not None:
            self._messages.close()
            self._messages = None

    def destroy_node(self) -> bool:
        self.close()
        return super().destroy_node()

    def describe(self) -> dict[str, Any]:
        return {
            "file": str(self.path),
            "rate": self.rate,
            "loop": self.loop,
            "published": self.published,
            "finished": self.finished,
            "skipped": self.skipped,
        }
