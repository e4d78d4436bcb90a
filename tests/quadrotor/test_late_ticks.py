"""A world that runs late (a class server short of CPU) flies slower than real time, not open-loop.

The executor is run as a starved world's would be: one pass every 50-150 ms of the clock instead
of every timer at its deadline, so each tick finds the drone flown for the whole gap on the last
command. Flown that way a late tick may fly at most one flight-controller period; the rest of the
gap is skipped, so the flight keeps its shape and only takes longer.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from node_runtime.bus import ManualClock
from server.packages.flightcontroller.angle_controller import RATE_HZ
from server.peripherals.devices.shared_physics import SharedQuadrotorPhysics, SharedSimpleSim
from server.world.lab import Lab

from .conftest import Probe, make_lab, node, start

STEP_M = np.array([-2.0, 0.0, 3.0])  # two presses left from the keyboard manager's home
ON_TIME_OVERSHOOT_M = 0.05  # the step flown on time overshoots 1.5 cm
LATE_S = (0.05, 0.15)  # how far apart a starved world's executor passes come
CONTROL_PERIOD_S = 1.0 / RATE_HZ  # the flight controllers' (50 Hz)


def fly_step(late: bool) -> tuple[Lab, Probe, float]:
    """Take off and settle on time, then fly the 2 m step for 20 s, on time or late; the step's start."""
    lab = make_lab("fly")
    probe = start(lab)
    lab.executor.spin_until(10.0)
    lab.publish("/uav/input/position", dict(zip("xyz", STEP_M.tolist(), strict=True)), None)
    step_at_s = lab.bus.clock.now()
    if not late:
        lab.executor.spin_until(step_at_s + 20.0)
        return lab, probe, step_at_s
    clock = lab.bus.clock
    assert isinstance(clock, ManualClock)
    rng = np.random.default_rng(7)
    while clock.now() < step_at_s + 20.0:
        clock.advance(float(rng.uniform(*LATE_S)))
        lab.executor.spin_some()
    return lab, probe, step_at_s


@pytest.fixture(scope="module", params=["on_time", "late"])
def flown(request: pytest.FixtureRequest) -> Iterator[tuple[str, Lab, Probe, float]]:
    lab, probe, step_at_s = fly_step(request.param == "late")
    yield request.param, lab, probe, step_at_s
    lab.launcher.shutdown()


def test_a_late_world_flies_the_step_with_the_same_shape(flown: tuple[str, Lab, Probe, float]) -> None:
    _, _, probe, step_at_s = flown
    p = probe.positions(after_s=step_at_s)[:, 1:]
    overshoot_m = STEP_M[0] - p[:, 0].min()
    assert overshoot_m < ON_TIME_OVERSHOOT_M
    assert np.abs(p[:, 2] - STEP_M[2]).max() < 0.02  # height held through the step
    assert np.abs(p[-20:] - STEP_M).max() < 0.1  # and it arrived


def test_a_late_world_runs_slower_than_real_time(flown: tuple[str, Lab, Probe, float]) -> None:
    mode, lab, _, _ = flown
    sim_s, clock_s = node(lab, "flightgoggles_uav_dynamics").sim.time_s, lab.bus.clock.now()
    if mode == "on_time":
        assert sim_s == pytest.approx(clock_s, abs=0.002)  # the sim keeps real time
    else:
        # Each pass flew at most one controller period of its 50-150 ms gap.
        assert sim_s < 10.0 + 20.0 * CONTROL_PERIOD_S / LATE_S[0] + 0.1
        assert sim_s > 10.0 + 20.0 * CONTROL_PERIOD_S / LATE_S[1] - 0.1


def test_the_class_batch_flies_a_long_gap_for_one_controller_period_only() -> None:
    clock = ManualClock(0.0)
    physics = SharedQuadrotorPhysics(clock)
    drones = [physics.add(seed, noise=False) for seed in (1, 2)]
    clock.advance(0.005)  # a short gap is flown whole
    physics.advance_to(clock.now())
    assert [d.state.time_s for d in drones] == pytest.approx([0.005, 0.005])
    clock.advance(0.5)  # a stall: one period flown, the rest skipped
    physics.advance_to(clock.now())
    assert [d.state.time_s for d in drones] == pytest.approx([0.025, 0.025])


def test_the_class_simple_sim_runs_the_ticks_a_short_stall_missed() -> None:
    clock = ManualClock(0.0)
    shared = SharedSimpleSim(clock)
    drone = shared.add(1, noise=False)
    clock.advance(0.1)  # two of its 20 Hz ticks: the lab's own timer callbacks, run late
    shared.advance_to(clock.now())
    assert drone.state.time_s == pytest.approx(0.1)
    clock.advance(1.0)  # a longer stall: two ticks, the rest skipped
    shared.advance_to(clock.now())
    assert drone.state.time_s == pytest.approx(0.2)
