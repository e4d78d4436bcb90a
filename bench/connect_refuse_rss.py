"""Bench: does a refused or closed socket leave anything behind? RSS and node count of a running
server over many connect/refuse cycles on the echo WebSocket.

    .venv/bin/python bench/connect_refuse_rss.py [--cycles 10000] [--sample-every 1000]

``python -m server --launch rocket`` (countdown held back, no browser) runs as a child process
on a free loopback port. Each cycle opens ``/ws/topics/countdown?type=std_msgs/msg/Bool`` (a type
that conflicts with the topic's, so the server refuses it with 4409 after the handshake) and
reads the close; every ``--closed-every`` cycles a socket that is accepted is opened and closed
instead. VmRSS and the hidden node count (``GET /api/nodes?hidden=true``) are sampled every
``--sample-every`` cycles after ``--warmup`` unmeasured cycles. Reported: RSS at the first and
last sample and the drift between them, the largest node count seen, cycles per second.
Results are printed with the machine's details and written to bench/results/connect_refuse_rss.json.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import sys
import tempfile
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import httpx
import websockets

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from live_server import LiveServer
from machine import machine_info

RESULTS = Path(__file__).resolve().parent / "results"
CYCLE_TIMEOUT_S = 10.0


async def one_cycle(ws_url: str, refused: bool) -> int | None:
    query = "?type=std_msgs/msg/Bool" if refused else ""
    async with (
        asyncio.timeout(CYCLE_TIMEOUT_S),
        websockets.connect(f"{ws_url}/ws/topics/countdown{query}") as ws,
    ):
        if refused:
            try:
                await ws.recv()
            except websockets.exceptions.ConnectionClosed as closed:
                return closed.rcvd.code if closed.rcvd else None
        return None


async def run_cycles(server: LiveServer, args: argparse.Namespace) -> dict[str, Any]:
    samples: list[dict[str, float]] = []
    codes: dict[str, int] = {}
    http = httpx.AsyncClient(base_url=server.url, timeout=5)

    async def sample(cycle: int) -> None:
        nodes = (await http.get("/api/nodes", params={"hidden": True})).json()
        samples.append({"cycle": cycle, "rss_mib": server.rss_mib(), "nodes": len(nodes)})

    start = time.perf_counter()
    for i in range(args.warmup + args.cycles):
        refused = (i % args.closed_every) != 0
        code = await one_cycle(server.ws_url, refused)
        if refused:
            codes[str(code)] = codes.get(str(code), 0) + 1
        if i >= args.warmup and (i - args.warmup) % args.sample_every == 0:
            await sample(i - args.warmup)
    elapsed = time.perf_counter() - start
    await sample(args.cycles)
    await http.aclose()
    return {"samples": samples, "close_codes": codes, "cycles_per_s": (args.warmup + args.cycles) / elapsed}


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--cycles", type=int, default=10_000)
    parser.add_argument("--warmup", type=int, default=500)
    parser.add_argument("--sample-every", type=int, default=1000)
    parser.add_argument(
        "--closed-every", type=int, default=10, help="every Nth cycle is accepted, then closed"
    )
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="bench_refuse_") as workdir:
        server = LiveServer(Path(workdir), "rocket", "start_delay:=3600")
        try:
            result = asyncio.run(run_cycles(server, args))
            result["log_problems"] = server.log_problems()[:20]
            for line in result["log_problems"]:
                print("server log:", line)
        finally:
            server.stop()
    samples = result["samples"]
    first, last = samples[0], samples[-1]
    summary = {
        "rss_first_mib": first["rss_mib"],
        "rss_last_mib": last["rss_mib"],
        "rss_drift_mib": last["rss_mib"] - first["rss_mib"],
        "nodes_first": first["nodes"],
        "nodes_max": max(s["nodes"] for s in samples),
        "nodes_last": last["nodes"],
        "cycles_per_s": result["cycles_per_s"],
        "close_codes": result["close_codes"],
        "log_problems": len(result["log_problems"]),
    }
    machine = machine_info()
    print(
        f"machine: {machine['cpu_model']} x{machine['nproc']}, Python {machine['python']}, "
        f"load at start {machine['load_average_at_start']}"
    )
    print(
        f"{args.cycles} connect/refuse cycles (+{args.warmup} warm-up), 1 in {args.closed_every} accepted then closed"
    )
    for sample in samples:
        print(f"  cycle {sample['cycle']:>6}: RSS {sample['rss_mib']:7.1f} MiB, nodes {sample['nodes']}")
    print(json.dumps(summary, indent=2))
    RESULTS.mkdir(exist_ok=True)
    out = {
        "when": datetime.now(UTC).isoformat(),
        "machine": machine,
        "args": vars(args),
        "summary": summary,
        **result,
    }
    (RESULTS / "connect_refuse_rss.json").write_text(json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
