"""Physics steps per second: one QuadrotorSim, a QuadrotorBatch of one, and N separate QuadrotorSims
against a QuadrotorBatch of N, all in the same run.

Run from the repository root:  .venv/bin/python bench/physics_batch.py [--runs 5] [--reference REF]

A physics step is one step of every drone: one QuadrotorBatch.step(), or one step() of each of
N QuadrotorSims. Every drone hovers with process noise on, at 1 kHz; the "grounded" column is a
batch whose drones all rest on the ground. The configurations are interleaved round by round and
each figure is the median over --runs rounds, so a busy machine slows them alike: read the
ratios. As timeit does, each timed loop runs with the garbage collector collected and paused. The simple mode (SimpleSimBatch against N SimpleSims, 20 Hz ticks) is timed the same way.
--reference REF also times one and N separate QuadrotorSims of git revision REF (for example
main), loaded from a temporary copy of that revision's sim/ package. Results go to
bench/results/physics_batch.json.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import numpy as np

REPO_ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO_ROOT))

from machine import machine_info, save_results

from sim.quadrotor import (
    QuadrotorBatch,
    QuadrotorSim,
    RateThrustCommand,
    SimpleSim,
    SimpleSimBatch,
)

SIZES = (1, 5, 10, 30, 60)
DT_S = 0.001
HOVER = RateThrustCommand((0.0, 0.0, 0.0), 9.81)
Bench = Callable[[int], float]  # steps -> steps per second


def _timed(step: Callable[[], None], steps: int) -> float:
    """Steps per second, with the garbage collector run before and kept out of the loop, as timeit does."""
    gc.collect()
    gc.disable()
    try:
        start = time.perf_counter()
        for _ in range(steps):
            step()
        return steps / (time.perf_counter() - start)
    finally:
        gc.enable()


def batched(n: int, airborne: bool = True) -> Bench:
    def run(steps: int) -> float:
        batch = QuadrotorBatch()
        for i in range(n):
            drone = batch.add(
                rng=np.random.default_rng(i),
                position_m=(i, 0.0, 3.0 if airborne else 0.0),
                rotors_at_hover=airborne,
            )
            drone.set_command(HOVER if airborne else RateThrustCommand((0.0, 0.0, 0.0), 0.0))
        return _timed(batch.step, steps)

    return run


def separate(n: int, sim_class: type = QuadrotorSim, command: object = HOVER) -> Bench:
    def run(steps: int) -> float:
        sims = []
        for i in range(n):
            sim = sim_class(
                rng=np.random.default_rng(i), initial_position_m=(i, 0.0, 3.0), rotors_at_hover=True
            )
            sim.set_command(command)
            sims.append(sim)
        if n == 1:
            return _timed(sims[0].step, steps)
        steppers = [sim.step for sim in sims]

        def step_all() -> None:
            for step in steppers:
                step()

        return _timed(step_all, steps)

    return run


def simple_batched(n: int) -> Bench:
    def run(ticks: int) -> float:
        batch = SimpleSimBatch()
        for i in range(n):
            batch.add(rng=np.random.default_rng(i)).set_velocity_command((0.1 * i, 0.2, 0.0))
        return _timed(batch.tick, ticks)

    return run


def simple_separate(n: int) -> Bench:
    def run(ticks: int) -> float:
        sims = [SimpleSim(rng=np.random.default_rng(i)) for i in range(n)]
        for i, sim in enumerate(sims):
            sim.set_velocity_command((0.1 * i, 0.2, 0.0))

        def tick_all() -> None:
            for sim in sims:
                sim.tick()

        return _timed(tick_all, ticks)

    return run


def load_reference(ref: str, workdir: Path) -> ModuleType:
    """sim.quadrotor as it was at git revision ref, imported from a copy without disturbing ours."""
    archive = subprocess.run(
        ["git", "-C", str(REPO_ROOT), "archive", "--format=tar", ref, "sim"], check=True, capture_output=True
    ).stdout
    tar_path = workdir / "sim.tar"
    tar_path.write_bytes(archive)
    with tarfile.open(tar_path) as tar:
        tar.extractall(workdir, filter="data")
    ours = {name: mod for name, mod in sys.modules.items() if name == "sim" or name.startswith("sim.")}
    for name in ours:
        del sys.modules[name]
    sys.path.insert(0, str(workdir))
    try:
        return importlib.import_module("sim.quadrotor")
    finally:
        sys.path.remove(str(workdir))
        for name in [n for n in sys.modules if n == "sim" or n.startswith("sim.")]:
            del sys.modules[name]
        sys.modules.update(ours)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--batch-steps", type=int, default=1000, help="physics steps per batched run")
    parser.add_argument(
        "--drone-steps", type=int, default=4000, help="drone-steps per separate run (split over N)"
    )
    parser.add_argument("--reference", help="git revision whose QuadrotorSim is also timed, e.g. main")
    args = parser.parse_args()
    if args.runs < 3:
        parser.error("--runs must be >= 3 (figures are medians)")

    info = machine_info()
    print("machine:", ", ".join(f"{k}={v}" for k, v in info.items()), flush=True)
    started = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        benches: dict[str, tuple[Bench, int]] = {}
        for n in SIZES:
            per_sim = max(50, args.drone_steps // n)
            benches[f"batched_{n}"] = (batched(n), args.batch_steps)
            benches[f"batched_grounded_{n}"] = (batched(n, airborne=False), args.batch_steps)
            benches[f"separate_{n}"] = (separate(n), per_sim)
            benches[f"simple_batched_{n}"] = (simple_batched(n), args.batch_steps)
            benches[f"simple_separate_{n}"] = (simple_separate(n), per_sim)
        if args.reference:
            ref = load_reference(args.reference, Path(tmp))
            info["reference"] = args.reference
            for n in SIZES:
                benches[f"reference_separate_{n}"] = (
                    separate(n, ref.QuadrotorSim, ref.RateThrustCommand((0.0, 0.0, 0.0), 9.81)),
                    max(50, args.drone_steps // n),
                )
        for bench, steps in benches.values():
            bench(max(10, steps // 10))  # warm-up
        runs: dict[str, list[float]] = {name: [] for name in benches}
        for r in range(args.runs):
            for name, (bench, steps) in benches.items():
                runs[name].append(bench(steps))
            print(f"round {r + 1}/{args.runs} done", flush=True)
    info["load_average_at_end"] = os.getloadavg()
    info["seconds"] = round(time.perf_counter() - started, 1)

    median = {name: statistics.median(rates) for name, rates in runs.items()}
    scalar, batch_of_one = median["separate_1"], median["batched_1"]
    print(f"\none drone at 1 kHz: QuadrotorSim {scalar:,.0f} steps/s ({scalar * DT_S:.1f}x real time)")
    print(
        f"  a QuadrotorBatch of one: {batch_of_one:,.0f} steps/s, {batch_of_one / scalar:.2f}x QuadrotorSim"
    )
    if args.reference:
        ref_one = median["reference_separate_1"]
        print(
            f"  QuadrotorSim of {args.reference}: {ref_one:,.0f} steps/s; ours is {scalar / ref_one:.2f}x that"
        )

    table = []
    header = f"\n{'N':>3} {'separate st/s':>14} {'batched st/s':>13} {'x real':>7} {'batch/sep':>10}"
    header += f" {'sep/ref':>8}" if args.reference else ""
    print(header + f" {'grounded st/s':>14} {'simple batch/sep':>17}")
    for n in SIZES:
        row = {
            "n": n,
            "separate_steps_per_s": median[f"separate_{n}"],
            "batched_steps_per_s": median[f"batched_{n}"],
            "batched_grounded_steps_per_s": median[f"batched_grounded_{n}"],
            "ratio": median[f"batched_{n}"] / median[f"separate_{n}"],
            "simple_separate_ticks_per_s": median[f"simple_separate_{n}"],
            "simple_batched_ticks_per_s": median[f"simple_batched_{n}"],
            "simple_ratio": median[f"simple_batched_{n}"] / median[f"simple_separate_{n}"],
        }
        if args.reference:
            row["reference_separate_steps_per_s"] = median[f"reference_separate_{n}"]
            row["separate_over_reference"] = median[f"separate_{n}"] / median[f"reference_separate_{n}"]
        table.append(row)
        line = f"{n:>3} {row['separate_steps_per_s']:>14,.0f} {row['batched_steps_per_s']:>13,.0f}"
        line += f" {row['batched_steps_per_s'] * DT_S:>6.1f}x {row['ratio']:>9.2f}x"
        line += f" {row['separate_over_reference']:>7.2f}x" if args.reference else ""
        line += f" {row['batched_grounded_steps_per_s']:>14,.0f} {row['simple_ratio']:>16.1f}x"
        print(line)
    print(f"({info['seconds']} s, load average at end {info['load_average_at_end']})")
    save_results("physics_batch", {"machine": info, "dt_s": DT_S, "table": table, "runs": runs})


if __name__ == "__main__":
    main()
