"""A page-like bench client: connects to a lab as an open lab page does and counts what each of
its channels carries a second.

    .venv/bin/python bench/page_client.py --url http://127.0.0.1:8000 [--token T] [--seconds 10]

The channels, as the page opens them (web/src/lab):

* ``viser``: viser's own WebSocket at ``/`` (subprotocol ``viser-v<version>``, carried by
  api/routes/page.py to the lab's viser server). Each frame is viser's batch: a 16-byte header (the
  msgpack's size, then the zstd payload's size, little-endian), the zstd-compressed msgpack
  ``{"messages": [...], ...}``, then binary buffers. Counted per message, split into
  ``viser_scene`` (scene nodes and their transforms), ``viser_gui`` (GUI widgets) and
  ``viser_other`` (the rest: theme, backlog markers, ...);
* ``pose_gps`` and ``pose_setpoint``: the HUD's pose stream, the echoes of ``/uav/sensors/gps``
  (its newest message every 20 ms: ``throttle_rate=20``) and ``/uav/input/position``
  (``queue_length=10``), as web/src/lab/poses.worker.ts opens them;
* ``keys``: the key channel ``/ws/keys``, sent a heartbeat every 200 ms as the page does
  (``keys_sent``); what it receives (errors only) is ``keys``.

A class world's token goes in the ``lab_token`` cookie, as the page's does; the Origin header is
the lab's own. Rates are messages a second over the window after ``--warm-s``.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import multiprocessing
import os
import statistics
import sys
import threading
import time
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

import msgspec
import viser
import websockets
import zstandard

HEARTBEAT_S = 0.2  # web/src/lab/keys.ts: HEARTBEAT_MS
POSE_TOPICS = {"pose_gps": "uav/sensors/gps", "pose_setpoint": "uav/input/position"}
# Each echo's query as the page's pose worker opens it: the newest pose every 20 ms
# (POSE_PERIOD_MS in web/src/lab/pose_ring.ts), every setpoint.
POSE_QUERIES = {"pose_gps": "throttle_rate=20", "pose_setpoint": "queue_length=10"}
HEADER_BYTES = 16
MAX_FRAME_BYTES = 64 * 1024 * 1024


def viser_messages(frame: bytes) -> list[dict[str, Any]]:
    """The messages of one frame viser's server sent (its batch layout, viser/infra/_infra.py)."""
    if len(frame) < HEADER_BYTES:
        raise ValueError(f"a viser frame of {len(frame)} bytes is shorter than its header")
    size = int.from_bytes(frame[:8], "little")
    compressed = int.from_bytes(frame[8:16], "little")
    if HEADER_BYTES + compressed > len(frame):
        raise ValueError("a viser frame shorter than its compressed payload says")
    inner = zstandard.ZstdDecompressor().decompress(frame[16 : 16 + compressed], max_output_size=size)
    batch = msgspec.msgpack.decode(inner)
    if not isinstance(batch, dict) or not isinstance(batch.get("messages"), list):
        raise ValueError("a viser frame without a list of messages")
    return [m for m in batch["messages"] if isinstance(m, dict)]


def channel_of(message_type: str) -> str:
    """Which of the page's viser channels a message belongs to, by viser's type name."""
    if message_type.startswith("Gui"):
        return "viser_gui"
    if message_type.startswith(("Scene", "Set", "Remove", "Frame", "Transform")) or "Scene" in message_type:
        return "viser_scene"
    return "viser_other"


@dataclass
class Counts:
    """Messages per channel (and viser's per type), with when the window opened."""

    channels: Counter[str] = field(default_factory=Counter)
    viser_types: Counter[str] = field(default_factory=Counter)
    since: float = field(default_factory=time.monotonic)

    def add_viser(self, frame: bytes) -> None:
        for message in viser_messages(frame):
            kind = str(message.get("type", "?"))
            self.viser_types[kind] += 1
            self.channels[channel_of(kind)] += 1

    def restart(self) -> None:
        self.channels.clear()
        self.viser_types.clear()
        self.since = time.monotonic()

    def rates(self) -> dict[str, float]:
        elapsed = max(time.monotonic() - self.since, 1e-9)
        return {name: count / elapsed for name, count in sorted(self.channels.items())}


class PageClient:
    """One open lab page's connections, counting; ``run`` for a bounded time."""

    def __init__(self, url: str, token: str | None = None) -> None:
        self.http = url.rstrip("/")
        self.ws = "ws" + self.http[len("http") :]
        self.headers = {"Origin": self.http}
        if token is not None:
            self.headers["Cookie"] = f"lab_token={token}"
        self.counts = Counts()
        self.errors: list[str] = []

    async def _viser(self) -> None:
        async with websockets.connect(
            self.ws + "/",
            subprotocols=[websockets.Subprotocol(f"viser-v{viser.__version__}")],
            additional_headers=self.headers,
            max_size=MAX_FRAME_BYTES,
            compression=None,
        ) as ws:
            async for frame in ws:
                if isinstance(frame, bytes):
                    self.counts.add_viser(frame)

    async def _pose(self, channel: str, topic: str) -> None:
        async with websockets.connect(
            f"{self.ws}/ws/topics/{topic}?{POSE_QUERIES[channel]}", additional_headers=self.headers
        ) as ws:
            async for _ in ws:
                self.counts.channels[channel] += 1

    async def _keys(self) -> None:
        async with websockets.connect(self.ws + "/ws/keys", additional_headers=self.headers) as ws:

            async def beat() -> None:
                while True:
                    await ws.send(json.dumps({"type": "heartbeat"}))
                    self.counts.channels["keys_sent"] += 1
                    await asyncio.sleep(HEARTBEAT_S)

            beating = asyncio.create_task(beat())
            try:
                async for _ in ws:
                    self.counts.channels["keys"] += 1
            finally:
                beating.cancel()

    async def _guarded(self, name: str, channel: Any) -> None:
        try:
            await channel
        except Exception as exc:  # a channel refused or closed: named in the report
            self.errors.append(f"{name}: {type(exc).__name__}: {exc}")

    async def run(self, seconds: float, warm_s: float = 2.0) -> dict[str, float]:
        """Open every channel, count for ``seconds`` after ``warm_s``, close; the rates."""

        async def window() -> dict[str, float]:
            await asyncio.sleep(warm_s)
            self.counts.restart()
            await asyncio.sleep(seconds)
            return self.counts.rates()

        return await self._open_while(window())

    async def hold(self, closed: asyncio.Event) -> None:
        """Every channel open until ``closed`` is set (``counts`` read by the caller)."""

        async def until() -> None:
            await closed.wait()

        await self._open_while(until())

    async def _open_while(self, body: Any) -> Any:
        channels = [self._guarded("viser", self._viser()), self._guarded("keys", self._keys())]
        channels += [self._guarded(name, self._pose(name, topic)) for name, topic in POSE_TOPICS.items()]
        tasks = [asyncio.create_task(c) for c in channels]
        try:
            return await body
        finally:
            for task in tasks:
                task.cancel()
            for task in tasks:
                with contextlib.suppress(asyncio.CancelledError):
                    await task


class PageClients:
    """Many page clients run together on a thread of their own (for a bench whose main thread
    waits): ``start``, then ``results`` once ``warm_s + seconds`` are over."""

    def __init__(self, clients: list[PageClient], seconds: float, warm_s: float) -> None:
        self.clients = clients
        self._rates: list[dict[str, float]] = []
        self._thread = threading.Thread(target=self._run, args=(seconds, warm_s), daemon=True)

    def _run(self, seconds: float, warm_s: float) -> None:
        async def every() -> list[dict[str, float]]:
            return list(await asyncio.gather(*(c.run(seconds, warm_s) for c in self.clients)))

        self._rates = asyncio.run(every())

    def start(self) -> None:
        self._thread.start()

    def results(self, timeout_s: float) -> tuple[list[dict[str, float]], list[str]]:
        """Each client's rates, and every channel error, once the run is over."""
        self._thread.join(timeout_s)
        if self._thread.is_alive():
            raise TimeoutError(f"the page clients did not finish within {timeout_s:g} s")
        return self._rates, [e for c in self.clients for e in c.errors]


class OpenPages:
    """Many page clients held open in a process of their own for as long as a bench needs (a
    burst, then a steady window): ``mark`` starts counting afresh, ``rates`` reads each client's
    since the mark, ``close`` closes them all.

    A process, not a thread of the bench's: a bench times the class's answers from its own
    threads, and a client thread run below them (``nice``) would hold the bench's interpreter lock
    whenever the scheduler paused it, so every timed call would wait for the pages' thread to run
    again. The clients (``url``, one per token) are made in that process; it runs ``nice`` below
    the bench."""

    def __init__(self, url: str, tokens: list[str], nice: int = 0) -> None:
        context = multiprocessing.get_context("spawn")  # nothing of the bench's threads goes along
        self._conn, child = context.Pipe()
        self._process = context.Process(target=_serve_pages, args=(url, tokens, nice, child), daemon=True)

    def open(self) -> None:
        self._process.start()
        self._ask("ready")

    @property
    def pid(self) -> int:
        assert self._process.pid is not None, "not open"
        return self._process.pid

    def _ask(self, what: str, timeout_s: float = 60.0) -> Any:
        self._conn.send(what)
        if not self._conn.poll(timeout_s):
            raise TimeoutError(f"the page clients' process did not answer {what!r} in {timeout_s:g} s")
        return self._conn.recv()

    def mark(self) -> None:
        self._ask("mark")

    def rates(self) -> tuple[list[dict[str, float]], list[str]]:
        """Each client's rates since the mark, and every channel error so far."""
        rates, errors = self._ask("rates")
        return rates, errors

    def close(self, timeout_s: float = 30.0) -> None:
        if self._process.is_alive():
            with contextlib.suppress(OSError, TimeoutError, EOFError):
                self._ask("close", timeout_s)
        self._process.join(timeout_s)
        if self._process.is_alive():
            self._process.kill()
            self._process.join(timeout_s)


def _serve_pages(url: str, tokens: list[str], nice: int, conn: Any) -> None:
    """The page clients' process: holds them open on a loop thread and answers the bench's asks."""
    if nice:
        os.nice(nice)
    clients = [PageClient(url, t) for t in tokens]
    loop = asyncio.new_event_loop()
    closed: asyncio.Event | None = None

    async def every() -> None:
        nonlocal closed
        closed = asyncio.Event()
        await asyncio.gather(*(c.hold(closed) for c in clients))

    thread = threading.Thread(target=loop.run_until_complete, args=(every(),), daemon=True)
    thread.start()

    def on_loop(call: Any) -> Any:
        async def run() -> Any:
            return call()

        return asyncio.run_coroutine_threadsafe(run(), loop).result(timeout=30)

    while True:
        what = conn.recv()
        if what == "ready":
            conn.send(None)
        elif what == "mark":
            on_loop(lambda: [c.counts.restart() for c in clients])
            conn.send(None)
        elif what == "rates":
            rates = on_loop(lambda: [c.counts.rates() for c in clients])
            conn.send((rates, [e for c in clients for e in c.errors]))
        elif what == "close":
            if closed is not None:
                loop.call_soon_threadsafe(closed.set)
            thread.join(30.0)
            conn.send(None)
            return


def median_rates(rates: list[dict[str, float]]) -> dict[str, float]:
    """Per channel, the median over clients of its rate (a client that got none counts 0)."""
    names = sorted({name for r in rates for name in r})
    return {name: round(statistics.median(r.get(name, 0.0) for r in rates), 1) for name in names}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--url", default="http://127.0.0.1:8000")
    parser.add_argument("--token", default=None, help="a class world's token (the page's cookie)")
    parser.add_argument("--seconds", type=float, default=10.0)
    parser.add_argument("--warm-s", type=float, default=2.0)
    args = parser.parse_args(argv)
    client = PageClient(args.url, args.token)
    rates = asyncio.run(client.run(min(args.seconds, 600.0), args.warm_s))
    print(
        json.dumps(
            {"rates_hz": rates, "viser_types": dict(client.counts.viser_types), "errors": client.errors},
            indent=2,
        )
    )
    return 1 if client.errors else 0


if __name__ == "__main__":
    sys.exit(main())
