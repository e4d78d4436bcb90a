"""A bag on disk as ``ros2 bag record`` writes one with its MCAP storage: a folder holding
``<name>_0.mcap`` (profile ``ros2``, ``ros2msg`` schemas with their dependencies, ``cdr``
channels carrying the type hash) and a ``metadata.yaml`` that ``ros2 bag info`` reads.

Writing happens on a thread of its own, fed by a bounded queue: the executor's thread only
serializes a message and enqueues its bytes, so a slow disk or a chunk being compressed never
holds up the sim. When the queue is full the newest message is dropped and counted.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import yaml
from mcap.writer import CompressionType, Writer

from node_runtime.msgs.wire import definition_closure_text, type_hash

log = logging.getLogger("bag")
ROS2_PROFILE = "ros2"
SCHEMA_ENCODING = "ros2msg"
MESSAGE_ENCODING = "cdr"
LIBRARY = "teleop-lab rosbag2-compatible writer"
# rosbag2's metadata format 5 (Humble's): every later rosbag2 reads it.
METADATA_VERSION = 5
QUEUE_MESSAGES = 10_000


@dataclass(frozen=True)
class BagMessage:
    topic: str
    type_name: str
    log_time_ns: int
    data: bytes


@dataclass
class BagStats:
    """What went into a bag so far; updated by the writer thread."""

    counts: Counter[str] = field(default_factory=Counter)
    types: dict[str, str] = field(default_factory=dict)
    start_ns: int | None = None
    end_ns: int | None = None
    bytes_written: int = 0
    dropped: int = 0

    @property
    def message_count(self) -> int:
        return sum(self.counts.values())

    def add(self, msg: BagMessage) -> None:
        self.counts[msg.topic] += 1
        self.types.setdefault(msg.topic, msg.type_name)
        self.start_ns = msg.log_time_ns if self.start_ns is None else min(self.start_ns, msg.log_time_ns)
        self.end_ns = msg.log_time_ns if self.end_ns is None else max(self.end_ns, msg.log_time_ns)
        self.bytes_written += len(msg.data)


class BagWriter:
    """One bag folder being written; ``submit`` from any thread, ``close`` once at the end."""

    def __init__(self, folder: Path, max_queue: int = QUEUE_MESSAGES) -> None:
        if folder.exists():
            raise FileExistsError(f"bag folder {folder} already exists")
        folder.mkdir(parents=True)
        self.folder = folder
        self.mcap_path = folder / f"{folder.name}_0.mcap"
        self.stats = BagStats()
        self._queue: queue.Queue[BagMessage | None] = queue.Queue(max_queue)
        self._stream = self.mcap_path.open("wb")
        self._writer = Writer(self._stream, compression=CompressionType.ZSTD)
        self._writer.start(profile=ROS2_PROFILE, library=LIBRARY)
        self._channels: dict[str, int] = {}
        self._schemas: dict[str, int] = {}
        self._closed = False
        self._thread = threading.Thread(target=self._run, name=f"bag-writer-{folder.name}", daemon=True)
        self._thread.start()

    def submit(self, msg: BagMessage) -> bool:
        """Queue one message; False (and counted) if the writer is behind by a full queue."""
        if self._closed:
            return False
        try:
            self._queue.put_nowait(msg)
        except queue.Full:
            self.stats.dropped += 1
            return False
        return True

    def close(self) -> None:
        """Write what is queued, the MCAP summary and metadata.yaml; blocks until done."""
        if not self._closed:
            self._closed = True
            self._queue.put(None)
        self._thread.join()

    def _run(self) -> None:
        try:
            while (msg := self._queue.get()) is not None:
                self._write(msg)
        except Exception:  # a full disk must not take the app down; the bag ends here
            log.exception("writing %s failed; the bag ends at the last message written", self.mcap_path)
            self._closed = True
        finally:
            self._finish()

    def _channel(self, topic: str, type_name: str) -> int:
        channel = self._channels.get(topic)
        if channel is None:
            schema = self._schemas.get(type_name)
            if schema is None:
                text = definition_closure_text(type_name).encode()
                schema = self._schemas[type_name] = self._writer.register_schema(
                    type_name, SCHEMA_ENCODING, text
                )
            metadata = {"offered_qos_profiles": "", "topic_type_hash": type_hash(type_name)}
            channel = self._writer.register_channel(topic, MESSAGE_ENCODING, schema, metadata)
            self._channels[topic] = channel
        return channel

    def _write(self, msg: BagMessage) -> None:
        channel = self._channel(msg.topic, msg.type_name)
        sequence = self.stats.counts[msg.topic] + 1
        self._writer.add_message(channel, msg.log_time_ns, msg.data, msg.log_time_ns, sequence)
        self.stats.add(msg)

    def _finish(self) -> None:
        try:
            self._writer.finish()  # type: ignore[no-untyped-call]  # mcap leaves it unannotated
        finally:
            self._stream.close()
        (self.folder / "metadata.yaml").write_text(yaml.safe_dump(self.metadata(), sort_keys=False))

    def metadata(self) -> dict[str, object]:
        """rosbag2's ``rosbag2_bagfile_information`` for this bag."""
        stats = self.stats
        start = stats.start_ns or 0
        duration = (stats.end_ns or start) - start
        topics = [
            {
                "topic_metadata": {
                    "name": topic,
                    "type": stats.types[topic],
                    "serialization_format": MESSAGE_ENCODING,
                    "offered_qos_profiles": "",
                },
                "message_count": count,
            }
            for topic, count in stats.counts.items()
        ]
        file_name = self.mcap_path.name
        return {
            "rosbag2_bagfile_information": {
                "version": METADATA_VERSION,
                "storage_identifier": "mcap",
                "duration": {"nanoseconds": duration},
                "starting_time": {"nanoseconds_since_epoch": start},
                "message_count": stats.message_count,
                "topics_with_message_count": topics,
                "compression_format": "",
                "compression_mode": "",
                "relative_file_paths": [file_name],
                "files": [
                    {
                        "path": file_name,
                        "starting_time": {"nanoseconds_since_epoch": start},
                        "duration": {"nanoseconds": duration},
                        "message_count": stats.message_count,
                    }
                ],
            }
        }
