"""What watching for checkpoints costs a world: the same world stepped with and without its watch.

One process, one world at a time on a manual clock (no wall-clock sleep, so the figure is CPU per
simulated second, which is the share of one core the world takes when it runs in real time): the
drone's launch (rotor physics, its controllers at their rates, GPS at the dynamics' rate), a 1 Hz
publisher to (5, 5, 10), and arrow keys every 2 s. Rounds alternate with and without the watch, so
both see the same machine load; the watch's own drain is timed too. Prints a table and writes
bench/results/checkpoint_watch.json.

    python bench/checkpoint_watch.py                  # 4 rounds of 30 simulated s
    python bench/checkpoint_watch.py --rounds 2 --sim-s 10
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from machine import machine_info, save_results

from node_runtime.bus import ManualClock
from server.host.settings import LabSettings, Settings
from server.world.lab import Lab

WARM_S = 3.0
ARROW_UP, ARROW_RIGHT = 273, 275  # SDL codes


def one_round(watch: bool, sim_s: float, state_dir: Path) -> dict[str, Any]:
    settings = Settings(lab=LabSettings(launch="fly", viewer=False, state_dir=state_dir, workspace=None))
    lab = Lab(settings, ManualClock())
    drain_s = [0.0]
    if watch:
        inner = lab.checkpoints.drain

        def timed() -> None:
            started = time.perf_counter()
            inner()
            drain_s[0] += time.perf_counter() - started

        lab.checkpoints.drain = timed  # type: ignore[method-assign]
        lab.checkpoints.start()
    lab.start_nodes()
    lab.publishers.start(
        "/uav/input/position", {"x": 5.0, "y": 5.0, "z": 10.0}, "geometry_msgs/msg/Vector3", 1.0
    )
    executor = lab.executor
    executor.spin_for(WARM_S)
    drain_s[0] = 0.0
    cpu0 = time.process_time()
    steps = int(sim_s / 2)
    for i in range(steps):
        code = ARROW_RIGHT if i % 2 else ARROW_UP
        lab.keyboard.key_down(code, 0, "bench")
        executor.spin_for(0.1)
        lab.keyboard.key_up(code, 0, "bench")
        executor.spin_for(1.9)
    cpu = time.process_time() - cpu0
    done = sorted(lab.checkpoints.progress.records) if watch else []
    lab.publishers.stop_all()
    lab.launcher.shutdown()
    for node in list(lab.bus.nodes):
        node.destroy_node()
    return {
        "watch": watch,
        "cpu_s": cpu,
        "sim_s": steps * 2.0,
        "drain_s": drain_s[0],
        "met": done,
        "dropped": lab.checkpoints.dropped,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=4)
    parser.add_argument("--sim-s", type=float, default=30.0)
    args = parser.parse_args()
    runs = []
    with tempfile.TemporaryDirectory() as state:
        for i in range(args.rounds):
            for watch in (i % 2 == 0, i % 2 == 1):  # alternate which goes first
                run = one_round(watch, args.sim_s, Path(state))
                runs.append(run)
                print(
                    f"round {i + 1} watch={watch!s:5}: {100 * run['cpu_s'] / run['sim_s']:6.2f} % of a core"
                    f"  (drain {100 * run['drain_s'] / run['sim_s']:.3f} %)  met={run['met']}",
                    flush=True,
                )
    share = {w: [r["cpu_s"] / r["sim_s"] for r in runs if r["watch"] is w] for w in (True, False)}
    drain = [r["drain_s"] / r["sim_s"] for r in runs if r["watch"]]
    summary = {
        "with_watch_pct": 100 * statistics.median(share[True]),
        "without_watch_pct": 100 * statistics.median(share[False]),
        "difference_pct": 100 * (statistics.median(share[True]) - statistics.median(share[False])),
        "drain_pct": 100 * statistics.median(drain),
    }
    print(
        f"median: with {summary['with_watch_pct']:.2f} %, without {summary['without_watch_pct']:.2f} %, "
        f"difference {summary['difference_pct']:.2f} % of a core; the watch's drain {summary['drain_pct']:.3f} %"
    )
    save_results(
        "checkpoint_watch", {"machine": machine_info(), "args": vars(args), "runs": runs, "summary": summary}
    )


if __name__ == "__main__":
    main()
