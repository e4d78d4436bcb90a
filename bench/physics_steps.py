"""Physics steps per second: our QuadrotorSim (+ cascade) against RotorPy's Multirotor (+ SE3Control).

Run from the repository root:  .venv/bin/python bench/physics_steps.py [--runs 5]
Each figure is the median over --runs runs of one headless drone stepped at dt = 1 ms.
RotorPy is optional (pip extra "bench"); without it only our figures are printed.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

REPO_ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO_ROOT))

from machine import machine_info

from sim.control import ClosedLoop
from sim.quadrotor import QuadrotorSim, RateThrustCommand

DT_S = 0.001
CONTROL_EVERY = 20  # our cascade runs at 50 Hz over 1 kHz physics


def ours_physics(steps: int) -> float:
    """Physics + on-board rate loop only, hover command held, process noise on."""
    sim = QuadrotorSim(rng=np.random.default_rng(1), initial_position_m=(0, 0, 3), rotors_at_hover=True)
    sim.set_command(RateThrustCommand((0.0, 0.0, 0.0), 9.81))
    start = time.perf_counter()
    for _ in range(steps):
        sim.step()
    return steps / (time.perf_counter() - start)


def ours_closed_loop(steps: int) -> float:
    """Physics at 1 kHz + position/velocity/angle cascade at 50 Hz, step (0,0,3) -> (5,5,10)."""
    sim = QuadrotorSim(rng=np.random.default_rng(1), initial_position_m=(0, 0, 3), rotors_at_hover=True)
    loop = ClosedLoop(sim)
    loop.set_position_setpoint((5.0, 5.0, 10.0))
    start = time.perf_counter()
    for _ in range(steps // CONTROL_EVERY):
        loop.tick()
    return steps / (time.perf_counter() - start)


def _rotorpy_setup(target: tuple[float, float, float]):  # type: ignore[no-untyped-def]
    from rotorpy.controllers.quadrotor_control import SE3Control  # type: ignore[import-untyped]
    from rotorpy.trajectories.hover_traj import HoverTraj  # type: ignore[import-untyped]
    from rotorpy.vehicles.hummingbird_params import quad_params  # type: ignore[import-untyped]
    from rotorpy.vehicles.multirotor import Multirotor  # type: ignore[import-untyped]

    vehicle = Multirotor(quad_params)
    state = {key: np.array(value, dtype=float) for key, value in vehicle.initial_state.items()}
    state["x"] = np.array([0.0, 0.0, 3.0])
    return vehicle, SE3Control(quad_params), HoverTraj(x0=np.array(target)), state


def rotorpy_physics(steps: int) -> float:
    """Multirotor.step only (scipy solve_ivp RK45 per step, its default), hover motor speeds held."""
    vehicle, controller, trajectory, state = _rotorpy_setup((0.0, 0.0, 3.0))
    control = controller.update(0.0, state, trajectory.update(0.0))
    start = time.perf_counter()
    for _ in range(steps):
        state = vehicle.step(state, control, DT_S)
    return steps / (time.perf_counter() - start)


def rotorpy_rk4_physics(steps: int) -> float:
    """RotorPy's own derivative (Multirotor._s_dot_fn, numpy) under a fixed-step RK4 like ours.

    Separates the integrator choice (adaptive RK45 via solve_ivp) from per-evaluation cost.
    """
    vehicle, controller, trajectory, state = _rotorpy_setup((0.0, 0.0, 3.0))
    control = controller.update(0.0, state, trajectory.update(0.0))
    cmd = vehicle.get_cmd_motor_speeds(state, control)
    s = rotorpy_pack_state(state)
    h = DT_S
    start = time.perf_counter()
    for _ in range(steps):
        k1 = vehicle._s_dot_fn(0.0, s, cmd)
        k2 = vehicle._s_dot_fn(0.0, s + 0.5 * h * k1, cmd)
        k3 = vehicle._s_dot_fn(0.0, s + 0.5 * h * k2, cmd)
        k4 = vehicle._s_dot_fn(0.0, s + h * k3, cmd)
        s = s + h / 6.0 * (k1 + 2.0 * (k2 + k3) + k4)
        s[6:10] /= np.linalg.norm(s[6:10])
    return steps / (time.perf_counter() - start)


def rotorpy_pack_state(state: dict[str, np.ndarray]) -> np.ndarray:
    from rotorpy.vehicles.multirotor import Multirotor  # type: ignore[import-untyped]

    return Multirotor._pack_state(state)


def rotorpy_closed_loop(steps: int) -> float:
    """Multirotor.step + SE3Control.update every step, as rotorpy.simulate does, step to (5,5,10)."""
    vehicle, controller, trajectory, state = _rotorpy_setup((5.0, 5.0, 10.0))
    start = time.perf_counter()
    for i in range(steps):
        t = i * DT_S
        state = vehicle.step(state, controller.update(t, state, trajectory.update(t)), DT_S)
    return steps / (time.perf_counter() - start)


def median_rate(bench: Callable[[int], float], steps: int, runs: int) -> dict[str, object]:
    bench(max(steps // 10, CONTROL_EVERY))  # warm-up: imports, caches
    rates = [bench(steps) for _ in range(runs)]
    return {"median_steps_per_s": statistics.median(rates), "runs_steps_per_s": rates, "steps_per_run": steps}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--ours-steps", type=int, default=20_000)
    parser.add_argument("--rotorpy-steps", type=int, default=2_000)
    parser.add_argument("--json", type=Path, default=REPO_ROOT / "bench" / "results" / "physics_steps.json")
    args = parser.parse_args()
    if args.runs < 5:
        parser.error("--runs must be >= 5 (figures are medians)")

    info = machine_info()
    print("machine:", ", ".join(f"{k}={v}" for k, v in info.items()))
    results: dict[str, dict[str, object]] = {
        "ours_physics": median_rate(ours_physics, args.ours_steps, args.runs),
        "ours_closed_loop": median_rate(ours_closed_loop, args.ours_steps, args.runs),
    }
    try:
        import rotorpy  # type: ignore[import-untyped]

        results["rotorpy_physics"] = median_rate(rotorpy_physics, args.rotorpy_steps, args.runs)
        results["rotorpy_rk4_physics"] = median_rate(rotorpy_rk4_physics, args.rotorpy_steps, args.runs)
        results["rotorpy_closed_loop"] = median_rate(rotorpy_closed_loop, args.rotorpy_steps, args.runs)
        info["rotorpy"] = getattr(rotorpy, "__version__", "installed")
    except ImportError:
        print("rotorpy not installed: skipping its figures")

    for name, result in results.items():
        rate = float(result["median_steps_per_s"])  # type: ignore[arg-type]
        print(f"{name:22s} {rate:12,.0f} steps/s  ({rate * DT_S:8.2f}x real time at 1 kHz)")
    ratios = {}
    for kind in ("physics", "closed_loop"):
        if f"rotorpy_{kind}" in results:
            ours = float(results[f"ours_{kind}"]["median_steps_per_s"])  # type: ignore[arg-type]
            theirs = float(results[f"rotorpy_{kind}"]["median_steps_per_s"])  # type: ignore[arg-type]
            ratios[kind] = ours / theirs
            print(f"ratio ours/rotorpy ({kind}): {ours / theirs:.1f}")

    args.json.parent.mkdir(parents=True, exist_ok=True)
    args.json.write_text(
        json.dumps({"machine": info, "dt_s": DT_S, "results": results, "ratios": ratios}, indent=2)
    )
    print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
