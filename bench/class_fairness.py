"""One student's worst against the rest of a class: does another world keep its rate?

``python -m server --classroom --launch fly`` in a child process, ``--quiet`` students and one
more, the "worst" student. A quiet window first: each quiet world's dynamics timer (100 Hz) is
read through /api/nodes, its calls over the window (the rate) and its tick lateness p99, with
the server's CPU. Then the worst student, from a process of its own at the lowest CPU priority
(on a real class its client is another machine), for ``--ramp`` s and the whole second window,
keeps trying fly launches in their world, resets it as fast as the server answers, and keeps up
to ``--sockets`` rosbridge sockets open, each subscribed to their drone's GPS and read; every
attempt is counted by its answer (started, refused with 429, closed 1013). The same quiet worlds
are measured meanwhile, and once more after it stops (the machine's own load moves between
windows). Prints the three windows, then the two figures the class's aim names, each against its
aim: the slowest quiet world's rate under the worst student as a share of the better quiet window
(at least 95 %), and the largest quiet world's tick lateness p99 under the worst student (under
10 ms); writes bench/results/class_fairness.json.

    python bench/class_fairness.py                           # 3 quiet worlds, 20 s windows
    python bench/class_fairness.py --only sockets --window 10
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections import Counter
from pathlib import Path
from typing import Any

import httpx

sys.path.insert(0, str(Path(__file__).resolve().parent))
from classroom_worlds import cpu_s, dynamics_timer
from live_server import LiveServer, end
from machine import machine_info, save_results

CODE = "FAIR01"
WARM_S = 5.0
FLY = {"package": "flightcontroller", "file": "fly.launch"}
ATTACKS = ("launches", "resets", "sockets")
RATE_AIM = 0.95  # of the quiet class's dynamics rate, in the same run
P99_AIM_MS = 10.0  # dynamics tick lateness p99
GPS = {"op": "subscribe", "topic": "/uav/sensors/gps", "type": "geometry_msgs/msg/PoseStamped"}


def join(server: LiveServer, name: str) -> str:
    """A student's token; a join refused for now (429) is tried again when the server says."""
    for _ in range(20):
        reply = httpx.post(f"{server.url}/api/classroom/join", json={"name": name, "code": CODE}, timeout=60)
        if reply.status_code != 429:
            reply.raise_for_status()
            return str(reply.json()["token"])
        time.sleep(float(reply.headers.get("Retry-After", "1")))
    raise RuntimeError(f"{name} could not join")


def window(server: LiveServer, tokens: list[str], seconds: float) -> dict[str, Any]:
    """Each world's dynamics rate over ``seconds`` (its own read times), its lateness p99 after,
    and the share of a core the server used meanwhile."""
    before = [(dynamics_timer(server, t)["calls"], time.monotonic()) for t in tokens]
    cpu0, t0 = cpu_s(server.proc.pid), time.monotonic()
    time.sleep(seconds)
    cpu1, t1 = cpu_s(server.proc.pid), time.monotonic()
    after = [(dynamics_timer(server, t), time.monotonic()) for t in tokens]
    rates = [(t["calls"] - c) / (at - since) for (t, at), (c, since) in zip(after, before, strict=True)]
    p99 = [t["lateness_p99_ms"] for t, _ in after]
    return {
        "dynamics_hz_min": round(min(rates), 1),
        "dynamics_hz_median": round(statistics.median(rates), 1),
        "lateness_p99_ms_max": round(max(p99), 2),
        "lateness_p99_ms_median": round(statistics.median(p99), 2),
        "server_cores": round((cpu1 - cpu0) / (t1 - t0), 2),
        "load_average_1min": round(os.getloadavg()[0], 1),
    }


class Worst:
    """The worst student: launches, resets and sockets, each on a thread of its own until ``stop``."""

    def __init__(self, server: LiveServer, token: str, max_sockets: int, attacks: list[str]) -> None:
        self.server, self.max_sockets = server, max_sockets
        self.headers = {"Authorization": f"Bearer {token}"}
        self.counts: Counter[str] = Counter()
        self.stop = threading.Event()
        self._lock = threading.Lock()
        every = {"launches": self._launch, "resets": self._reset, "sockets": self._sockets}
        self._threads = [threading.Thread(target=every[a], daemon=True) for a in attacks]

    def start(self) -> None:
        for thread in self._threads:
            thread.start()

    def end(self) -> dict[str, int]:
        self.stop.set()
        for thread in self._threads:
            thread.join(timeout=30)
        return dict(sorted(self.counts.items()))

    def _count(self, what: str) -> None:
        with self._lock:
            self.counts[what] += 1

    def _launch(self) -> None:
        with httpx.Client(base_url=self.server.url, headers=self.headers, timeout=30) as http:
            while not self.stop.is_set():
                self._count(f"launch {http.post('/api/launch', json=FLY).status_code}")
                self.stop.wait(0.05)

    def _reset(self) -> None:
        with httpx.Client(base_url=self.server.url, headers=self.headers, timeout=30) as http:
            while not self.stop.is_set():
                self._count(f"reset {http.post('/api/classroom/worlds/worst/reset').status_code}")

    def _sockets(self) -> None:
        from websockets.exceptions import ConnectionClosed, InvalidStatus
        from websockets.sync.client import ClientConnection, connect

        open_: list[ClientConnection] = []
        try:
            while not self.stop.is_set():
                for ws in list(open_):  # read what each one got; drop the closed ones (a reset closes them)
                    try:
                        while ws.recv(timeout=0) is not None:
                            pass
                    except TimeoutError:
                        continue
                    except ConnectionClosed:
                        open_.remove(ws)
                if len(open_) >= self.max_sockets:
                    self.stop.wait(0.01)
                    continue
                try:
                    ws = connect(
                        f"{self.server.ws_url}/rosbridge", additional_headers=self.headers, max_size=None
                    )
                except (OSError, InvalidStatus, ConnectionClosed) as exc:  # refused, or closed by a reset
                    self._count(f"socket refused {type(exc).__name__}")
                    self.stop.wait(0.05)
                    continue
                try:
                    ws.send(json.dumps(GPS))
                    ws.recv(timeout=0.5)
                except TimeoutError:
                    pass
                except ConnectionClosed as closed:
                    code = closed.rcvd.code if closed.rcvd is not None else "none"
                    self._count(f"socket closed {code}")
                    continue
                self._count("socket open")
                open_.append(ws)
        finally:
            for ws in open_:
                with contextlib.suppress(ConnectionClosed):
                    ws.close()


def attack(url: str, token: str, seconds: float, sockets: int, attacks: list[str]) -> None:
    """The worst student, in a process of its own at the lowest CPU priority: on a real class its
    client runs on its own machine, so its client-side work must not take the server's CPU here.
    Prints what its attempts got, as JSON."""
    os.nice(19)
    server = LiveServer.__new__(LiveServer)  # only its addresses: the server is the parent's
    server.url, server.ws_url = url, url.replace("http://", "ws://")
    worst = Worst(server, token, sockets, attacks)
    worst.start()
    time.sleep(seconds)
    attempts = worst.end()
    with httpx.Client(base_url=url, headers=worst.headers, timeout=30) as http:  # quiet again: stop them
        for group in http.get("/api/launches").json():
            http.delete(f"/api/launches/{group['id']}")
    print(json.dumps(attempts), flush=True)


def run(quiet: int, window_s: float, ramp_s: float, sockets: int, attacks: list[str]) -> dict[str, Any]:
    with tempfile.TemporaryDirectory() as tmp:
        server = LiveServer(
            Path(tmp),
            "fly",
            "--classroom",
            "--class-code",
            CODE,
            "--max-worlds",
            str(quiet + 1),
            "--workers",
            "0",  # every world in the one process whose fairness this measures
        )
        try:
            tokens = [join(server, f"quiet {i}") for i in range(quiet)]
            worst_token = join(server, "worst")
            time.sleep(WARM_S)
            calm = window(server, tokens, window_s)
            attacker = subprocess.Popen(
                [
                    sys.executable,
                    __file__,
                    "--attack",
                    server.url,
                    worst_token,
                    str(ramp_s + window_s + 2),
                    "--sockets",
                    str(sockets),
                    "--only",
                    *attacks,
                ],
                stdout=subprocess.PIPE,
                text=True,
            )
            try:
                time.sleep(ramp_s)
                loaded = window(server, tokens, window_s)
                out, _ = attacker.communicate(timeout=60)
            finally:
                end(attacker)
            calm_again = window(server, tokens, window_s)
            problems = server.log_problems()
        finally:
            server.stop()
    return {
        "quiet": calm,
        "worst_student": loaded,
        "quiet_again": calm_again,
        "attempts": json.loads(out),
        "log_problems": problems[:5],
    }


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quiet", type=int, default=3, help="quiet worlds measured (default 3)")
    parser.add_argument("--window", type=float, default=20.0, help="each measuring window, s (default 20)")
    parser.add_argument(
        "--ramp", type=float, default=5.0, help="the worst student's head start, s (default 5)"
    )
    parser.add_argument(
        "--sockets", type=int, default=100, help="rosbridge sockets the worst student tries to hold"
    )
    parser.add_argument(
        "--only",
        nargs="+",
        choices=ATTACKS,
        default=list(ATTACKS),
        help="what the worst student does (default: all)",
    )
    parser.add_argument("--attack", nargs=3, metavar=("URL", "TOKEN", "SECONDS"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.attack:
        attack(args.attack[0], args.attack[1], float(args.attack[2]), args.sockets, args.only)
        return
    info = machine_info()
    print(f"machine: {info['cpu_model']}, {info['nproc']} CPUs, Python {info['python']}", flush=True)
    result = run(args.quiet, args.window, args.ramp, args.sockets, args.only)
    calm, loaded, again = result["quiet"], result["worst_student"], result["quiet_again"]
    for label, row in (("quiet class", calm), ("worst student", loaded), ("quiet again", again)):
        print(
            f"{label:>14}: dynamics Hz min/median {row['dynamics_hz_min']}/{row['dynamics_hz_median']}, "
            f"tick lateness p99 ms max/median {row['lateness_p99_ms_max']}/{row['lateness_p99_ms_median']}, "
            f"server {row['server_cores']} core, load average {row['load_average_1min']}"
        )
    ratio = loaded["dynamics_hz_min"] / max(calm["dynamics_hz_min"], again["dynamics_hz_min"])
    p99 = loaded["lateness_p99_ms_max"]
    print(f"the worst student's attempts: {result['attempts']}")
    print(
        f"aim 1, rate: the slowest quiet world keeps {ratio:.1%} of its quiet rate under the worst "
        f"student (aim: at least {RATE_AIM:.0%}): {'met' if ratio >= RATE_AIM else 'missed'}"
    )
    quiet_p99 = min(calm["lateness_p99_ms_max"], again["lateness_p99_ms_max"])
    print(
        f"aim 2, lateness: the quiet worlds' largest tick lateness p99 under the worst student is {p99} ms "
        f"(quiet class in this run: {quiet_p99} ms; aim: under {P99_AIM_MS:g} ms): "
        f"{'met' if p99 < P99_AIM_MS else 'missed'}",
        flush=True,
    )
    if result["log_problems"]:
        print("   server log:", result["log_problems"], flush=True)
    name = "class_fairness" + ("" if len(args.only) == len(ATTACKS) else "_" + "_".join(args.only))
    save_results(
        name,
        {
            "machine": info,
            "window_s": args.window,
            "ramp_s": args.ramp,
            "attacks": args.only,
            "ratio": round(ratio, 3),
            "rate_aim_met": ratio >= RATE_AIM,
            "p99_aim_met": p99 < P99_AIM_MS,
            **result,
        },
    )


if __name__ == "__main__":
    main()
