"""The lab's recordings and playbacks: what the REST API, the CLI and the page's record button use.

Bags live in one folder (``Settings.bag_dir``), each in a subfolder named like ros2 bag's
(``rosbag2_2025_01_31-12_00_00``) or as asked. Names are plain (letters, digits, ``_ . -``), so
a request can never write outside that folder. Recordings and playbacks are bounded in number,
and a recording in size.
"""

from __future__ import annotations

import itertools
import re
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from node_runtime.bus import Bus
from server.peripherals.bag.errors import (
    BagBusyError,
    BagError,
    BagExistsError,
    BagLimitError,
    BagNotFoundError,
)
from server.peripherals.bag.player import PlayerNode, mcap_file
from server.peripherals.bag.recorder import RecorderNode
from server.peripherals.bag.writer import BagWriter

NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]{0,99}$")
MAX_RECORDINGS = 4
MAX_PLAYERS = 4
KEPT_FINISHED = 16
MAX_BAG_BYTES = 512 * 1024 * 1024


def _inside(path: Path, folder: Path) -> bool:
    """``path`` exists and is in ``folder`` once links are followed (a link to elsewhere is not)."""
    try:
        return path.exists() and path.resolve().is_relative_to(folder.resolve())
    except OSError:
        return False


def default_bag_name(now_s: float | None = None) -> str:
    """``rosbag2_YYYY_MM_DD-HH_MM_SS``, as ros2 bag record names a bag it is not told a name for."""
    return time.strftime("rosbag2_%Y_%m_%d-%H_%M_%S", time.localtime(now_s))


def check_name(name: str) -> str:
    if not NAME.match(name) or name in (".", ".."):
        raise BagError(f"a bag name is letters, digits, '_', '.', '-' (at most 100), got {name!r}")
    return name


@dataclass
class Recording:
    name: str
    writer: BagWriter
    node: RecorderNode

    @property
    def active(self) -> bool:
        return self.node.state != "destroyed"

    def describe(self) -> dict[str, Any]:
        stats = self.writer.stats
        return {
            "name": self.name,
            "recording": self.active,
            "topics": self.node.recorded_topics,
            "messages": stats.message_count,
            "counts": dict(stats.counts),
            "dropped": stats.dropped,
            "bytes": stats.bytes_written,
            "size_limited": self.node.full,
            "file": self.writer.mcap_path.name,
        }


class BagManager:
    def __init__(self, bus: Bus, folder: Path, max_bag_bytes: int = MAX_BAG_BYTES) -> None:
        self.bus = bus
        self.folder = folder
        self.max_bag_bytes = max_bag_bytes
        self.recordings: dict[str, Recording] = {}
        self.players: dict[str, PlayerNode] = {}
        self._player_ids = itertools.count(1)

    # -- recording -------------------------------------------------------
    def record(
        self, topics: Iterable[str] = (), *, all_topics: bool = False, name: str | None = None
    ) -> Recording:
        """Start recording; the bag is written until ``stop_recording``."""
        topics = list(topics)
        if not all_topics and not topics:
            raise BagError("name the topics to record, or record all of them")
        if sum(r.active for r in self.recordings.values()) >= MAX_RECORDINGS:
            raise BagLimitError(f"already {MAX_RECORDINGS} recordings running; stop one first")
        name = check_name(default_bag_name() if name is None else name)
        if name in self.recordings or (self.folder / name).exists():
            raise BagExistsError(f"a bag named {name!r} already exists")
        writer = BagWriter(self.folder / name)
        try:
            with self.bus.activate():
                node = RecorderNode(
                    writer,
                    topics,
                    all_topics=all_topics,
                    max_bytes=self.max_bag_bytes,
                    node_name=self._node_name("rosbag2_recorder"),
                )
        except Exception:
            writer.close()
            raise
        recording = self.recordings[name] = Recording(name, writer, node)
        return recording

    def detach_recording(self, name: str) -> Recording:
        """Stop the recorder node (on the bus's thread); the caller then closes the writer,
        which may wait on the disk (``writer.close``)."""
        recording = self.recordings.get(name)
        if recording is None:
            raise BagNotFoundError(f"no recording named {name!r}")
        if recording.active:
            recording.node.flush()
            recording.node.destroy_node()
        return recording

    def stop_recording(self, name: str) -> Recording:
        recording = self.detach_recording(name)
        recording.writer.close()
        return recording

    def detach_bag(self, name: str) -> tuple[Path, Recording | None]:
        """Forget a bag (stopping its recorder node if it still records, and its playbacks); the
        caller closes the recording's writer, then deletes the returned folder (both may wait on
        the disk)."""
        folder = self.folder / check_name(name)
        recording = self.recordings.get(name)
        if recording is None and not folder.is_dir():
            raise BagNotFoundError(f"no bag named {name!r}")
        if recording is not None:
            self.detach_recording(name)
            del self.recordings[name]
        for player_id, player in list(self.players.items()):
            if player.path.parent.resolve() == folder.resolve():
                self.stop_player(player_id)
        return folder, recording

    def bag_file(self, name: str) -> Path:
        """The MCAP file of a finished bag in the bag folder."""
        recording = self.recordings.get(check_name(name))
        if recording is not None and recording.active:
            raise BagBusyError(f"{name} is still being recorded; stop it first")
        if not (self.folder / name).is_dir():
            raise BagNotFoundError(f"no bag named {name!r}")
        return mcap_file(self.folder / name)

    def list_bags(self) -> list[dict[str, Any]]:
        """This run's recordings, then older bags found in the folder."""
        out = [r.describe() for r in self.recordings.values()]
        if self.folder.is_dir():
            for path in sorted(self.folder.iterdir()):
                if path.is_dir() and path.name not in self.recordings and any(path.glob("*.mcap")):
                    out.append({"name": path.name, "recording": False})
        return out

    # -- playing ---------------------------------------------------------
    def bag_to_play(self, bag: str, *, confined: bool) -> Path:
        """What ``ros2 bag play BAG`` opens: a bag's name in the bag folder, else (unless
        ``confined``) a path to a bag folder or .mcap file. Confined, anything that is not a bag
        of this folder gets one answer, so it tells nothing of what exists elsewhere."""
        in_folder = self.folder / bag
        if NAME.match(bag) and (_inside(in_folder, self.folder) if confined else in_folder.exists()):
            return in_folder
        if confined:
            raise BagNotFoundError(
                f"no bag named {bag[:200]!r} in this world's bag folder: play a bag by its name, "
                "as GET /api/bag/recordings lists them"
            )
        return Path(bag)

    def play(self, path: Path, *, rate: float = 1.0, loop: bool = False) -> tuple[str, PlayerNode]:
        self.reap_players()
        if sum(not p.finished for p in self.players.values()) >= MAX_PLAYERS:
            raise BagLimitError(f"already {MAX_PLAYERS} bags playing; stop one first")
        with self.bus.activate():
            node = PlayerNode(path, rate=rate, loop=loop, node_name=self._node_name("rosbag2_player"))
        player_id = f"play{next(self._player_ids)}"
        self.players[player_id] = node
        return player_id, node

    def player(self, player_id: str) -> PlayerNode:
        self.reap_players()
        node = self.players.get(player_id)
        if node is None:
            raise BagNotFoundError(f"no playback with id {player_id!r}")
        return node

    def stop_player(self, player_id: str) -> PlayerNode:
        node = self.player(player_id)
        del self.players[player_id]
        node.destroy_node()
        return node

    def reap_players(self) -> None:
        """A finished playback's node leaves the graph, as ros2 bag play exits at the end of a
        bag; its record stays (the newest few) so a client can read how it went."""
        for node in self.players.values():
            if node.finished and node.state != "destroyed":
                node.destroy_node()
        finished = [pid for pid, node in self.players.items() if node.state == "destroyed"]
        for player_id in finished[:-KEPT_FINISHED]:
            del self.players[player_id]

    def stop_all(self) -> None:
        for player_id in list(self.players):
            self.stop_player(player_id)
        for name, recording in self.recordings.items():
            if recording.active:
                self.stop_recording(name)

    def _node_name(self, base: str) -> str:
        taken = {n.get_name() for n in self.bus.nodes}
        return next(
            n for n in itertools.chain([base], (f"{base}_{i}" for i in itertools.count(2))) if n not in taken
        )
