"""What one reader has seen of a launch group's output, and the frames that bring it up to date.

Each node process keeps its last lines (a bounded buffer, server/host/processes/supervisor.py) and
how many it printed in all, so a reader that fell behind learns how many lines it lost (a
``dropped`` frame) instead of holding up the process; then come its lines, each with its number
in the process's output (``seq``), and once the process has ended and every line is read, its
exit. A process that waits for its turn to start (server/host/processes/start_pacing.py) is first a
``waiting`` frame; one stopped before it started ends with an exit frame of no code and no
signal. A process that starts is a ``started`` frame with its pid (what ``ros2 launch`` logs as
"process started with pid"), then, once its Zenoh session has declared a node in the lab's graph,
a ``joined`` frame with the node's name: until then a page shows it as starting. A group has ended when each of its processes has and no node of it runs any more (a node
with ``respawn`` keeps it open while the group is not stopped).

The supervisor merges a process's stderr into its stdout (as a terminal shows them), so every
line's ``stream`` is ``stdout``.
"""

from __future__ import annotations

import signal
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from typing_extensions import TypedDict

from server.host.processes.supervisor import ProcessNode
from server.services.launch.groups import LaunchGroup


class LineFrame(TypedDict):
    """A line a node process printed; ``seq``: its number in the process's output."""

    type: Literal["line"]
    seq: int
    node: str
    stream: Literal["stdout", "stderr"]
    text: str


class DroppedFrame(TypedDict):
    """Lines a fast printer lost (its bounded buffer) before this reader read them."""

    type: Literal["dropped"]
    count: int


class WaitingFrame(TypedDict):
    """A node process that waits for its turn to start."""

    type: Literal["waiting"]
    node: str


class StartedFrame(TypedDict):
    """A node process started (its interpreter runs; its node is not in the graph yet)."""

    type: Literal["started"]
    node: str
    pid: int


class JoinedFrame(TypedDict):
    """A node process's session declared its node(s) in the lab's graph: ``names``, fully
    qualified."""

    type: Literal["joined"]
    node: str
    names: list[str]


class ExitFrame(TypedDict):
    """A node process ended: its exit code, or the signal that ended it; neither for one stopped
    before it started."""

    type: Literal["exit"]
    node: str
    code: int | None
    signal: str | None


class EndFrame(TypedDict):
    """Every node of the group has ended: the last frame."""

    type: Literal["end"]


Frame = LineFrame | DroppedFrame | WaitingFrame | StartedFrame | JoinedFrame | ExitFrame | EndFrame
# The nodes a node process's session (its Zenoh id) has declared in the lab's graph, or none yet.
JoinedNames = Callable[[str], list[str]]


@dataclass
class _Seen:
    process: ProcessNode
    node: str
    sent: int = 0  # lines of its output sent (or counted as dropped)
    exited: bool = False  # its exit frame sent
    waiting: bool = False  # its waiting frame sent
    started: bool = False  # its started frame sent
    joined: bool = False  # its joined frame sent


def exit_frame(process: ProcessNode, node: str) -> ExitFrame:
    code = process.exit_code
    if code is not None and code < 0:
        try:
            name: str | None = signal.Signals(-code).name
        except ValueError:
            name = f"signal {-code}"
        return {"type": "exit", "node": node, "code": None, "signal": name}
    return {"type": "exit", "node": node, "code": code, "signal": None}


class GroupOutput:
    """One reader's place in a group's output. ``running`` says whether the group is still in its
    lab (not stopped); ``joined`` which nodes a session has declared in the lab's graph."""

    def __init__(self, group: LaunchGroup, running: Callable[[], bool], joined: JoinedNames) -> None:
        self.group = group
        self.running = running
        self.joined = joined
        self._seen: list[_Seen] = []
        self.ended = False

    def _track(self) -> None:
        for entry in self.group.entries:
            process = entry.process
            if process is not None and all(s.process is not process for s in self._seen):
                self._seen.append(_Seen(process, process.label))

    def poll(self) -> list[Frame]:
        """The frames since the last poll (``ended`` turns true with the last of them)."""
        if self.ended:
            return []
        self._track()
        frames: list[Frame] = []
        for seen in self._seen:
            if seen.exited:
                continue
            if seen.process.proc is None:  # not started: waiting for its turn, or stopped first
                if seen.process.state == "waiting" and not seen.waiting:
                    frames.append({"type": "waiting", "node": seen.node})
                    seen.waiting = True
                elif seen.process.state in ("stopped", "died"):
                    frames.append({"type": "exit", "node": seen.node, "code": None, "signal": None})
                    seen.exited = True
                continue
            ended = seen.process.exit_code is not None  # read first: once set, every line is kept
            frames.extend(self._arrival(seen))
            lines, printed = seen.process.output()
            first = printed - len(lines)
            if seen.sent < first:
                frames.append({"type": "dropped", "count": first - seen.sent})
                seen.sent = first
            for index in range(seen.sent - first, len(lines)):
                frames.append(
                    {
                        "type": "line",
                        "seq": first + index,
                        "node": seen.node,
                        "stream": "stdout",
                        "text": lines[index],
                    }
                )
            seen.sent = printed
            if ended:
                frames.append(exit_frame(seen.process, seen.node))
                seen.exited = True
        if self._finished():
            frames.append({"type": "end"})
            self.ended = True
        return frames

    def _arrival(self, seen: _Seen) -> list[Frame]:
        """Its started frame, then its joined frame once its session has a node in the graph."""
        process, out = seen.process, list[Frame]()
        if not seen.started and process.proc is not None:
            out.append({"type": "started", "node": seen.node, "pid": process.proc.pid})
            seen.started = True
        if not seen.joined and process.exit_code is None:
            names = self.joined(process.command.zid)
            if names:
                out.append({"type": "joined", "node": seen.node, "names": names})
                seen.joined = True
        return out

    def _finished(self) -> bool:
        if not all(s.exited for s in self._seen):
            return False
        running = self.running()
        for entry in self.group.entries:
            if entry.node is not None:
                return False  # a node inside the lab's process, until the group is stopped
            if entry.process is not None and entry.process.exit_code is None:
                return False
            if running and entry.action.respawn:
                return False  # its node starts again after a crash, until the group is stopped
        return True
