"""Bench: what a class's router logins and access control cost a sample that crosses the router.

    .venv/bin/python bench/zenoh_acl.py [--messages 20000] [--rounds 5] [--size 64]

Two routers, each in a child process of its own on a free loopback port with multicast scouting
off: one plain (no login, no access control, as one lab without --token), one as a class server
opens it (node_runtime/transport/acl.py: a login file and the access-control list of every world domain,
default deny). In each round, for each router in turn, a publisher and a subscriber (Zenoh
clients in this process; on the class router both log in as world 1, as a student's node
processes do) exchange ``--messages`` samples of ``--size`` bytes on ``1/bench/chatter``,
reliable, blocking when congested so none is dropped. Timed from the first put to the last
sample's callback. Reports each router's median msgs/s over the rounds and their ratio (the class
router's over the plain one's). The children are ended by their own pids.
"""

from __future__ import annotations

import argparse
import json
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

import zenoh

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from live_server import end, free_port
from machine import machine_info, save_results

from node_runtime.transport.acl import FIRST_WORLD_DOMAIN, LAST_DOMAIN, ClassAuth, Credentials, RouterAccess
from node_runtime.transport.config import ZenohSettings
from node_runtime.transport.session import build_config, open_session

SECRET = "bench-instructor-token"
# A class server draws its worlds' logins at random; the bench's two processes need to agree on
# them, so these are fixed, one per world domain as in a full class.
WORLDS = {
    d: Credentials(f"ros2lab-world-{d}-bench", f"{SECRET}-{d}")
    for d in range(FIRST_WORLD_DOMAIN, LAST_DOMAIN + 1)
}
KEY = "1/bench/chatter"
READY_S = 20.0
ROUND_TIMEOUT_S = 120.0


def serve_router(kind: str, endpoint: str) -> None:
    """The child: a router, plain or as a class server opens it, until stdin closes."""
    session = open_session(
        ZenohSettings(
            listen=(endpoint,),
            router_logins=RouterAccess(ClassAuth(SECRET).class_credentials(), WORLDS)
            if kind == "class"
            else None,
        )
    )
    print("ready", flush=True)
    try:
        signal.pause()  # until the bench's Ctrl-C (live_server.end)
    except KeyboardInterrupt:
        pass
    finally:
        session.close()


def start_router(kind: str) -> tuple[subprocess.Popen[str], str]:
    endpoint = f"tcp/127.0.0.1:{free_port()}"
    child = subprocess.Popen(
        [sys.executable, __file__, "--serve-router", kind, endpoint], stdout=subprocess.PIPE, text=True
    )
    assert child.stdout is not None
    deadline = time.monotonic() + READY_S
    line = ""
    while time.monotonic() < deadline and not line:
        line = child.stdout.readline().strip()
    if line != "ready":
        end(child)
        raise SystemExit(f"the {kind} router did not start")
    return child, endpoint


def one_round(endpoint: str, login: Credentials | None, messages: int, size: int) -> float:
    """msgs/s from the first put to the last callback."""
    settings = ZenohSettings(mode="client", listen=(), connect=(endpoint,), login=login)
    got = 0
    done = threading.Event()
    last = [0.0]

    def on_sample(_sample: object) -> None:
        nonlocal got
        got += 1
        if got == messages:
            last[0] = time.perf_counter()
            done.set()

    with zenoh.open(build_config(settings)) as sub_session, zenoh.open(build_config(settings)) as pub_session:
        subscriber = sub_session.declare_subscriber(KEY, on_sample)
        publisher = pub_session.declare_publisher(
            KEY, congestion_control=zenoh.CongestionControl.BLOCK, reliability=zenoh.Reliability.RELIABLE
        )
        # Wait until the route is there: a probe that arrives resets the count.
        deadline = time.monotonic() + READY_S
        while got == 0 and time.monotonic() < deadline:
            publisher.put(b"probe")
            time.sleep(0.05)
        got = 0
        payload = bytes(size)
        started = time.perf_counter()
        for _ in range(messages):
            publisher.put(payload)
        finished = done.wait(ROUND_TIMEOUT_S)
        subscriber.undeclare()
        publisher.undeclare()
    if not finished:
        raise SystemExit(f"only {got} of {messages} samples arrived")
    return messages / (last[0] - started)


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--messages", type=int, default=20000)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--serve-router", nargs=2, metavar=("KIND", "ENDPOINT"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.serve_router:
        serve_router(*args.serve_router)
        return
    if not (1 <= args.messages <= 1_000_000 and 1 <= args.rounds <= 50 and 1 <= args.size <= 1 << 20):
        parser.error("--messages 1..1e6, --rounds 1..50, --size 1..1 MiB")
    info = machine_info()
    print(json.dumps(info), flush=True)
    routers: dict[str, tuple[subprocess.Popen[str], str]] = {}
    login = {"plain": None, "class": WORLDS[1]}
    rates: dict[str, list[float]] = {"plain": [], "class": []}
    try:
        for kind in ("plain", "class"):
            routers[kind] = start_router(kind)
        for _ in range(args.rounds):
            for kind, (_child, endpoint) in routers.items():
                rates[kind].append(one_round(endpoint, login[kind], args.messages, args.size))
    finally:
        for child, _endpoint in routers.values():
            end(child)
    medians = {kind: statistics.median(r) for kind, r in rates.items()}
    results = {
        "machine": info,
        "messages": args.messages,
        "size": args.size,
        "rounds": args.rounds,
        "msgs_per_s": {kind: [round(r) for r in rs] for kind, rs in rates.items()},
        "median_msgs_per_s": {kind: round(m) for kind, m in medians.items()},
        "ratio_class_over_plain": round(medians["class"] / medians["plain"], 3),
    }
    print(json.dumps(results, indent=2), flush=True)
    save_results("zenoh_acl", results)


if __name__ == "__main__":
    main()
