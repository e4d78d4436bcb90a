"""Bench: the Foxglove channel, against foxglove-sdk serving the same payloads with no bus behind it.

    .venv/bin/python bench/foxglove_bench.py [--flat-s 10] [--latency-s 20]

Two servers, each in a subprocess of its own, the same client for both (in this process, a
``websockets`` client speaking foxglove.sdk.v1, subscribed to one channel):

* ``sdk``: ``foxglove.start_server`` on loopback and a thread logging a geometry_msgs/PoseStamped
  in CDR on one channel, flat out, or at 100 Hz; nothing else.
* ``lab``: the app's bridge as ``python -m server`` runs it (a bus, the bridge node subscribed on
  demand, the app's own guarded Foxglove server the client connects to), with a node
  publishing PoseStamped on /bench/pose flat out (batches of 200, yielding to the loop between
  them) or at 100 Hz from a bus timer.

Measured: messages per second the client receives over ``--flat-s``; at 100 Hz, the latency of
each message from its header stamp (set by the publisher at publish time, wall clock) to its
arrival at the client, p50/p99 over ``--latency-s``. Results are JSON in bench/results/.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import signal
import statistics
import struct
import subprocess
import sys
import threading
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from live_server import end
from machine import machine_info

RESULTS = REPO / "bench" / "results"
TOPIC = "/bench/pose"
TYPE = "geometry_msgs/msg/PoseStamped"
READY_S = 60.0


def pose_cdr(stamp_s: float) -> bytes:
    from node_runtime.msgs import PoseStamped
    from node_runtime.msgs.wire import serialize

    msg = PoseStamped()
    sec = int(stamp_s)
    msg.header.stamp.sec, msg.header.stamp.nanosec = sec, int((stamp_s - sec) * 1e9)
    msg.header.frame_id = "world"
    msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = 1.0, 2.0, 3.0
    return serialize(msg)


# -- the servers (run as ``--serve sdk|lab MODE PORTFILE``) -----------------------------------
def serve_sdk(mode: str, port_file: Path) -> None:
    import foxglove
    from foxglove import Channel, Schema

    from node_runtime.msgs.wire import definition_closure_text

    ctx = foxglove.Context()
    server = foxglove.start_server(host="127.0.0.1", port=0, context=ctx)
    schema = Schema(name=TYPE, encoding="ros2msg", data=definition_closure_text(TYPE).encode())
    channel = Channel(TOPIC, message_encoding="cdr", schema=schema, context=ctx)
    port_file.write_text(str(server.port))

    def run() -> None:
        while True:
            if mode == "flat":
                payload = pose_cdr(time.time())
                for _ in range(200):
                    channel.log(payload)
            else:
                channel.log(pose_cdr(time.time()))
                time.sleep(0.01)

    threading.Thread(target=run, daemon=True).start()
    signal.sigwait({signal.SIGTERM, signal.SIGINT})


def serve_lab(mode: str, port_file: Path) -> None:
    import api  # noqa: F401  # first: the bridges use api's guard, and api's package imports the bridges
    from node_runtime.bus import Node
    from node_runtime.msgs import PoseStamped
    from server.host.settings import LabSettings, Settings
    from server.services.bridges.runner import run_bridges
    from server.world.lab import Lab

    async def main() -> None:
        lab = Lab(
            Settings(
                lab=LabSettings(
                    launch="rocket", viewer=False, foxglove_port=0, launch_args={"start_delay": "3600"}
                )
            )
        )
        await lab.start()
        async with run_bridges(lab) as bridges:
            with lab.bus.activate():
                node = Node("bench_talker")
            pub = node.create_publisher(PoseStamped, TOPIC, 10)

            def publish() -> None:
                msg = PoseStamped()
                now = lab.bus.clock.now()
                sec = int(now)
                msg.header.stamp.sec, msg.header.stamp.nanosec = sec, int((now - sec) * 1e9)
                msg.pose.position.x, msg.pose.position.y, msg.pose.position.z = 1.0, 2.0, 3.0
                pub.publish(msg)

            if mode == "rate":
                node.create_timer(0.01, publish)
            await asyncio.to_thread(port_file.write_text, str(bridges.foxglove_port))
            stop = asyncio.Event()
            loop = asyncio.get_running_loop()
            for sig in (signal.SIGTERM, signal.SIGINT):
                loop.add_signal_handler(sig, stop.set)
            while not stop.is_set():
                if mode == "flat":
                    for _ in range(200):
                        publish()
                    await asyncio.sleep(0)
                else:
                    await asyncio.wait({asyncio.ensure_future(stop.wait())}, timeout=1.0)
        await lab.stop()

    asyncio.run(main())


# -- the client ---------------------------------------------------------------------------------
async def measure(port: int, duration_s: float, latency: bool) -> dict[str, Any]:
    import websockets
    from mcap.records import Schema as McapSchema
    from mcap_ros2.decoder import DecoderFactory

    async with websockets.connect(
        f"ws://127.0.0.1:{port}", subprotocols=["foxglove.sdk.v1"], max_size=None
    ) as ws:
        channel = None
        while channel is None:
            msg = json.loads(await ws.recv())
            if msg["op"] == "advertise":
                channel = next((c for c in msg["channels"] if c["topic"] == TOPIC), None)
        schema = McapSchema(
            id=1, name=channel["schemaName"], encoding="ros2msg", data=channel["schema"].encode()
        )
        decode = DecoderFactory().decoder_for("cdr", schema)
        await ws.send(
            json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": channel["id"]}]})
        )
        count, lat_ms = 0, []
        start = time.monotonic()
        warm_until = start + 1.0
        end = warm_until + duration_s
        async for frame in ws:
            now = time.monotonic()
            if now > end:
                break
            if isinstance(frame, str) or frame[0] != 1 or now < warm_until:
                continue
            count += 1
            if latency:
                stamp = decode(frame[13:]).header.stamp
                lat_ms.append((time.time() - (stamp.sec + stamp.nanosec / 1e9)) * 1000)
                if struct.unpack_from("<I", frame, 1)[0] != 1:
                    raise RuntimeError("frame for another subscription")
    out: dict[str, Any] = {"messages": count, "rate_per_s": count / duration_s}
    if latency and lat_ms:
        lat_ms.sort()
        out.update(p50_ms=statistics.median(lat_ms), p99_ms=lat_ms[int(0.99 * (len(lat_ms) - 1))])
    return out


def run_server(kind: str, mode: str) -> tuple[subprocess.Popen[bytes], int]:
    port_file = RESULTS / f".fox_{kind}_{os.getpid()}.port"
    port_file.unlink(missing_ok=True)
    proc = subprocess.Popen([sys.executable, __file__, "--serve", kind, mode, str(port_file)], cwd=REPO)
    deadline = time.monotonic() + READY_S
    while not (port_file.exists() and port_file.read_text()):
        if proc.poll() is not None or time.monotonic() > deadline:
            raise RuntimeError(f"the {kind} server did not start")
        time.sleep(0.1)
    port = int(port_file.read_text())
    port_file.unlink()
    return proc, port


def stop(proc: subprocess.Popen[bytes]) -> None:
    end(proc, 15.0, signal.SIGTERM)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--flat-s", type=float, default=10.0)
    parser.add_argument("--latency-s", type=float, default=20.0)
    parser.add_argument("--serve", nargs=3, metavar=("KIND", "MODE", "PORTFILE"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve:
        kind, mode, port_file = args.serve
        (serve_sdk if kind == "sdk" else serve_lab)(mode, Path(port_file))
        return
    RESULTS.mkdir(parents=True, exist_ok=True)
    results: dict[str, Any] = {"machine": machine_info(), "when": datetime.now(UTC).isoformat()}
    for kind in ("sdk", "lab"):
        for mode, duration, latency in (("flat", args.flat_s, False), ("rate", args.latency_s, True)):
            proc, port = run_server(kind, mode)
            try:
                results[f"{kind}_{mode}"] = asyncio.run(measure(port, duration, latency))
            finally:
                stop(proc)
            print(kind, mode, results[f"{kind}_{mode}"], flush=True)
    results["lab_vs_sdk_flat_rate"] = results["lab_flat"]["rate_per_s"] / results["sdk_flat"]["rate_per_s"]
    out = RESULTS / f"foxglove_{datetime.now(UTC).strftime('%Y%m%dT%H%M%S')}.json"
    out.write_text(json.dumps(results, indent=2))
    print(f"lab/sdk flat-out rate: {results['lab_vs_sdk_flat_rate']:.2f}; written to {out.relative_to(REPO)}")


if __name__ == "__main__":
    main()
