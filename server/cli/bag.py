"""``bag record | play | info``, as ros2 bag takes and prints them.

``record`` has the server record (its bag folder keeps a copy the page can offer for download)
and, on Ctrl-C, fetches the bag into a folder here, named by ``-o`` or as ros2 bag names one.
``play`` has the server publish a bag with its timing until it ends (or Ctrl-C). ``info`` reads
a bag here, with no server, and prints what ``ros2 bag info`` prints.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from mcap.reader import make_reader

from server.cli.client import CliError, LabClient

POLL_S = 0.2
MCAP_MAGIC = b"\x89MCAP0\r\n"
INDENT = " " * 19  # ros2 bag info's column: the longest label ("Topic information: ")


def bag_record(
    args: argparse.Namespace, client: LabClient, sleep: Callable[[float], None] = time.sleep
) -> int:
    if not args.all and not args.topics:
        raise CliError("name the topics to record, or -a for all of them")
    if args.all and args.topics:
        raise CliError("-a records every topic: give either -a or topic names")
    out = Path(args.output) if args.output else None
    if out is not None and out.exists():
        raise CliError(f"output folder {out} already exists")
    body: dict[str, Any] = {"topics": args.topics, "all": args.all}
    if out is not None:
        body["name"] = out.name
    name = client.post("/api/bag/recordings", body)["name"]
    print(f"[INFO] [rosbag2_recorder]: Recording to '{name}'... (Ctrl-C to stop)", flush=True)
    try:
        while True:
            sleep(POLL_S)
    except KeyboardInterrupt:
        pass
    summary = client.post(f"/api/bag/recordings/{name}/stop", {})
    folder = out if out is not None else Path(name)
    folder.mkdir(parents=True)
    client.download(f"/api/bag/recordings/{name}/download", folder / summary["file"])
    client.download(f"/api/bag/recordings/{name}/metadata.yaml", folder / "metadata.yaml")
    print(
        f"[INFO] [rosbag2_recorder]: Recorded {summary['messages']} messages on "
        f"{len(summary['counts'])} topics into '{folder}'"
    )
    if summary["dropped"]:
        print(f"[WARN] [rosbag2_recorder]: {summary['dropped']} messages were dropped (the disk fell behind)")
    return 0


def bag_play(args: argparse.Namespace, client: LabClient, sleep: Callable[[float], None] = time.sleep) -> int:
    local = Path(args.bag_path)
    bag = str(local.resolve()) if local.exists() else args.bag_path  # else a bag in the server's folder
    player = client.post("/api/bag/players", {"bag": bag, "rate": args.rate, "loop": args.loop})
    for topic, why in player.get("skipped", {}).items():
        print(f"[WARN] [rosbag2_player]: not playing {topic}: {why}")
    try:
        while not player["finished"]:
            sleep(POLL_S)
            player = client.get(f"/api/bag/players/{player['id']}")
    except KeyboardInterrupt:
        client.delete(f"/api/bag/players/{player['id']}")
        return 0
    print(f"[INFO] [rosbag2_player]: Played {player['published']} messages from '{player['file']}'")
    return 0


@dataclass(frozen=True)
class BagInfo:
    files: list[str]
    size_bytes: int
    start_ns: int
    end_ns: int
    topics: list[tuple[str, str, int, str]]  # name, type, count, serialization format

    @property
    def message_count(self) -> int:
        return sum(count for _, _, count, _ in self.topics)


def read_info(path: Path) -> BagInfo:
    """A bag's summary from its MCAP file(s): the file itself or the bag folder."""
    files = sorted(path.glob("*.mcap")) if path.is_dir() else [path]
    if not files or not all(f.is_file() for f in files):
        raise CliError(f"no bag at {path}")
    counts: dict[tuple[str, str, str], int] = {}
    start, end = None, None
    for file in files:
        with file.open("rb") as f:
            if f.read(len(MCAP_MAGIC)) != MCAP_MAGIC:
                raise CliError(f"{file} is not an MCAP file")
            f.seek(0)
            summary = make_reader(f).get_summary()
        if summary is None or summary.statistics is None:
            raise CliError(f"{file} has no summary (was the recording cut off?)")
        stats = summary.statistics
        for channel_id, channel in summary.channels.items():
            schema = summary.schemas.get(channel.schema_id)
            key = (channel.topic, schema.name if schema else "", channel.message_encoding)
            counts[key] = counts.get(key, 0) + stats.channel_message_counts.get(channel_id, 0)
        if stats.message_count:
            start = stats.message_start_time if start is None else min(start, stats.message_start_time)
            end = stats.message_end_time if end is None else max(end, stats.message_end_time)
    topics = [(name, type_name, count, fmt) for (name, type_name, fmt), count in counts.items()]
    return BagInfo(
        [f.name for f in files], sum(f.stat().st_size for f in files), start or 0, end or 0, topics
    )


def format_size(size_bytes: int) -> str:
    size, units = float(size_bytes), ("B", "KiB", "MiB", "GiB", "TiB")
    index = 0
    while size >= 1024 and index < len(units) - 1:
        size /= 1024
        index += 1
    return f"{size:.0f} {units[index]}" if index == 0 else f"{size:.1f} {units[index]}"


def _seconds(ns: int) -> str:
    return f"{ns // 1_000_000_000}.{ns // 1_000_000 % 1000:03d}"


def _time_point(ns: int) -> str:
    local = time.localtime(ns // 1_000_000_000)
    return f"{time.strftime('%b %e %Y %H:%M:%S', local)}.{ns // 1_000_000 % 1000:03d} ({_seconds(ns)})"


def format_info(info: BagInfo) -> str:
    """``ros2 bag info``'s layout (rosbag2's format_bag_meta_data), milliseconds zero-padded."""
    lines = ["", "Files:             " + (f"\n{INDENT}".join(info.files))]
    lines += [
        f"Bag size:          {format_size(info.size_bytes)}",
        "Storage id:        mcap",
        f"Duration:          {_seconds(info.end_ns - info.start_ns)}s",
        f"Start:             {_time_point(info.start_ns)}",
        f"End:               {_time_point(info.end_ns)}",
        f"Messages:          {info.message_count}",
    ]
    topic_lines = [
        f"Topic: {name} | Type: {type_name} | Count: {count} | Serialization Format: {fmt}"
        for name, type_name, count, fmt in info.topics
    ]
    lines.append("Topic information: " + f"\n{INDENT}".join(topic_lines))
    return "\n".join(lines)


def bag_info(args: argparse.Namespace, _client: LabClient) -> int:
    print(format_info(read_info(Path(args.bag_path))))
    return 0


def _rate(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"the rate is a number, got {text!r}") from None
    if not 0.01 <= value <= 100:
        raise argparse.ArgumentTypeError(f"the rate must be in 0.01..100, got {value:g}")
    return value


def add_parser(verbs: Any, common: argparse.ArgumentParser) -> None:
    parser = verbs.add_parser("bag", help="Various rosbag related sub-commands")
    sub = parser.add_subparsers(dest="bag_verb", required=True, metavar="VERB")

    p = sub.add_parser("record", parents=[common], help="Record ROS data to a bag")
    p.add_argument("topics", nargs="*", metavar="TOPIC", help="topics to record")
    p.add_argument("-a", "--all", action="store_true", help="Record all topics (hidden ones excepted)")
    p.add_argument("-o", "--output", help="Destination of the bagfile (default: rosbag2_<date>)")
    p.set_defaults(handler=bag_record)

    p = sub.add_parser("play", parents=[common], help="Play back ROS data from a bag")
    p.add_argument("bag_path", help="Bag to open (its folder or .mcap file, or a bag's name on the server)")
    p.add_argument("-r", "--rate", type=_rate, default=1.0, help="rate at which to play back messages")
    p.add_argument("-l", "--loop", action="store_true", help="enables loop playback when playing a bagfile")
    p.set_defaults(handler=bag_play)

    p = sub.add_parser("info", parents=[common], help="Print information about a bag to the screen")
    p.add_argument("bag_path", help="Bag to open (its folder or .mcap file)")
    p.set_defaults(handler=bag_info)
