"""QuadrotorBatch: n quadrotors stepped together, one vectorized pass per physics step for all of them.

Drones join and leave while it runs (students come and go). Each drone has its own seeded
numpy Generator for its process noise, and a step is QuadrotorSim's step for every column, the
same operations in the same order and elementwise across drones. So a drone steps bit for bit
as a QuadrotorSim with the same seed and commands would, alone or among any others: its column
never mixes with another drone's, whatever they are commanded to do.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sim.quadrotor.dynamics import FLAT_TO_ROWS, ONES_ROW, POS, QUAT, RATES, ROTORS, VEL
from sim.quadrotor.fixed_step import FixedStepClock
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rate_control import RateGains
from sim.quadrotor.slots import DroneHandle, SlotTable
from sim.quadrotor.state import Command, Kinematics, MotorSpeedCommand, QuadrotorState, RateThrustCommand
from sim.quadrotor.step_kernel import BASE, MOTOR_CMD, RATES_CMD, ROWS, StepKernel
from sim.quadrotor.vehicle import (
    NOISE_BLOCK,
    clamp_motor_speeds,
    clamp_rate_thrust,
    draw_noise,
    noise_scale,
    not_a_command,
    physics_step_s,
    rest_command,
    rest_state,
)
from sim.types import FloatsLike


class QuadrotorBatch:
    """Quadrotors of one model stepped together at a fixed physics rate; time moves only through step()/advance().

    add() returns a Drone handle: set its command and read its state between steps. The model
    and each step are those of QuadrotorSim: the on-board rate loop and mixer or direct motor
    commands, motor lag, RK4, drag, process noise, ground contact. For one drone, QuadrotorSim is
    the faster choice; the batch pays numpy's per-call cost once per step for all its drones.
    """

    def __init__(self, params: QuadrotorParams | None = None, *, physics_rate_hz: float = 1000.0) -> None:
        self.dt_s = physics_step_s(physics_rate_hz)
        self.params = params if params is not None else QuadrotorParams()
        self.physics_rate_hz = float(physics_rate_hz)
        self._clock = FixedStepClock(self.physics_rate_hz)
        self._per_thrust = RateGains(self.params, self.dt_s).per_thrust
        self._noise_scale = noise_scale(self.params, self.dt_s)
        self._slots = SlotTable(
            {
                "floats": ((ROWS,), float),
                "noise": ((NOISE_BLOCK, 6), float),
                "on_ground": ((), bool),
                "motor": ((), bool),
            }
        )
        self._noise_due: dict[int, set[int]] = {}  # step index mod NOISE_BLOCK -> drones drawing then
        self._steps = 0
        self._kernel: StepKernel | None = None
        self._motor_cols = self._faulted_cols = np.empty(0, dtype=np.intp)

    def __len__(self) -> int:
        return len(self._slots)

    @property
    def drones(self) -> tuple[Drone, ...]:
        """Handles of the drones in the batch, oldest first."""
        return tuple(Drone(self, i) for i in self._slots.ids)

    def add(
        self,
        *,
        rng: np.random.Generator | None = None,
        noise: bool = True,
        position_m: FloatsLike = (0.0, 0.0, 0.0),
        yaw_rad: float = 0.0,
        rotors_at_hover: bool = False,
    ) -> Drone:
        """A new drone at rest at position_m, level, facing yaw_rad; with noise, rng must be its own generator."""
        if noise and rng is None:
            raise ValueError("noise=True needs a seeded numpy.random.Generator as rng")
        rest_state(self.params, position_m, yaw_rad, rotors_at_hover)  # ValueError before it joins
        drone_id = self._slots.add(rng if noise else None, self._steps)
        self._rebuild()
        self.reset(drone_id, position_m, yaw_rad, rotors_at_hover)
        return Drone(self, drone_id)

    def remove(self, drone_id: int) -> None:
        """Take a drone out; the others keep their state and their replay. DroneRemovedError if unknown."""
        self._slots.remove(drone_id)
        for due in self._noise_due.values():
            due.discard(drone_id)
        self._rebuild()

    def reset(
        self,
        drone_id: int,
        position_m: FloatsLike = (0.0, 0.0, 0.0),
        yaw_rad: float = 0.0,
        rotors_at_hover: bool = False,
    ) -> None:
        """Put one drone at rest at position_m (z clamped to >= 0), level, its clock at 0, command cleared."""
        flat = rest_state(self.params, position_m, yaw_rad, rotors_at_hover)
        col = self._slots.column(drone_id)
        floats = self._slots.arrays["floats"]
        floats[:, col] = 0.0
        floats[FLAT_TO_ROWS, col] = flat
        floats[ONES_ROW, col] = 1.0
        self._slots.arrays["on_ground"][col] = floats[POS.stop - 1, col] <= 0.0
        member = self._slots.record(drone_id)
        member.start_step, member.fault = self._steps, None
        self._faulted_cols = self._faulted_columns()
        if member.rng is not None:  # a fresh block of noise is drawn at its next step
            for due in self._noise_due.values():
                due.discard(drone_id)
            self._noise_due.setdefault(self._steps % NOISE_BLOCK, set()).add(drone_id)
        self.set_command(drone_id, rest_command(self.params, rotors_at_hover))

    def set_command(self, drone_id: int, command: Command) -> None:
        """Hold a new input for one drone. Raises ValueError (and keeps the old one) if invalid."""
        col = self._slots.column(drone_id)
        floats, motor = self._slots.arrays["floats"], self._slots.arrays["motor"]
        if isinstance(command, RateThrustCommand):
            rates, thrust = clamp_rate_thrust(self.params, command)
            floats[RATES_CMD, col] = rates
            floats[BASE, col] = thrust * self._per_thrust  # the thrust's share of the squared rotor speeds
            motor[col] = False
        elif isinstance(command, MotorSpeedCommand):
            floats[MOTOR_CMD, col] = clamp_motor_speeds(self.params, command)
            motor[col] = True
        else:
            raise not_a_command(command)
        self._motor_cols = np.flatnonzero(motor)

    def state(self, drone_id: int) -> QuadrotorState:
        """A frozen copy of one drone's current state."""
        col = self._slots.column(drone_id)
        s = self._slots.arrays["floats"][:, col]
        return QuadrotorState(
            time_s=self.time_s(drone_id),
            position_m=s[POS],
            velocity_m_s=s[VEL],
            attitude_wxyz=s[QUAT],
            body_rates_rad_s=s[RATES],
            rotor_speeds_rad_s=s[ROTORS],
            on_ground=bool(self._slots.arrays["on_ground"][col]),
        )

    def kinematics(self, drone_id: int) -> Kinematics:
        """One drone's position, velocity, attitude and body rates as floats (see Kinematics)."""
        f = self._slots.arrays["floats"][0:13, self._slots.column(drone_id)].tolist()
        return (f[6], f[7], f[8], f[0], f[1], f[2], f[9], f[10], f[11], f[12], f[3], f[4], f[5])

    def time_s(self, drone_id: int) -> float:
        """One drone's simulated time since it joined or was reset (s): its steps times dt."""
        return (self._steps - self._slots.record(drone_id).start_step) * self.dt_s

    def fault(self, drone_id: int) -> str | None:
        """Why a drone is frozen, or None. A step that would leave a drone's state non-finite keeps
        its previous state and freezes it until reset; with clamped inputs this cannot happen."""
        return self._slots.record(drone_id).fault

    @property
    def has_faults(self) -> bool:
        """True while any drone is frozen by a fault (see fault())."""
        return bool(self._faulted_cols.size)

    def advance(self, duration_s: float) -> int:
        """Step every drone for duration_s of simulated time; the part short of a step carries over. Returns steps."""
        return self._clock.run(duration_s, self.step)

    def step(self) -> None:
        """One physics step for every drone: rate loop and mixer, RK4, renormalise, rate clamp, ground."""
        cursor = self._steps % NOISE_BLOCK
        due = self._noise_due.get(cursor)
        if due:
            self._draw_noise(due, cursor)
        if self._kernel is not None:
            self._step_drones(self._kernel, cursor)
        self._steps += 1

    def _step_drones(self, kernel: StepKernel, cursor: int) -> None:
        bad = kernel.step(self._slots.arrays["noise"][cursor], self._motor_cols, self._faulted_cols)
        if bad.size:
            records = self._slots.records
            for col in bad:
                member = records[col]
                if member.fault is None:
                    t = (self._steps - member.start_step) * self.dt_s
                    member.fault = f"non-finite quadrotor state after step at t={t:.3f} s"
            self._faulted_cols = self._faulted_columns()

    def _draw_noise(self, drone_ids: set[int], cursor: int) -> None:
        """A block of noise per drone, laid out so that the batch's step cursor reads it in draw order."""
        noise = self._slots.arrays["noise"]
        rows = (cursor + np.arange(NOISE_BLOCK)) % NOISE_BLOCK
        for drone_id in drone_ids:
            rng = self._slots.record(drone_id).rng
            assert rng is not None
            noise[rows, :, self._slots.column(drone_id)] = draw_noise(rng, self._noise_scale)

    def _faulted_columns(self) -> npt.NDArray[np.intp]:
        return np.array([c for c, r in enumerate(self._slots.records) if r.fault is not None], dtype=np.intp)

    def _rebuild(self) -> None:
        arrays = self._slots.arrays
        self._kernel = (
            StepKernel(arrays["floats"], arrays["on_ground"], self.params, self.dt_s)
            if len(self._slots)
            else None
        )
        self._motor_cols = np.flatnonzero(self._slots.arrays["motor"])
        self._faulted_cols = self._faulted_columns()


class Drone(DroneHandle["QuadrotorBatch"]):
    """One drone of a QuadrotorBatch: read its state and set its command between the batch's steps."""

    __slots__ = ()

    @property
    def state(self) -> QuadrotorState:
        return self._batch.state(self.id)

    def kinematics(self) -> Kinematics:
        return self._batch.kinematics(self.id)

    @property
    def fault(self) -> str | None:
        return self._batch.fault(self.id)

    def set_command(self, command: Command) -> None:
        self._batch.set_command(self.id, command)

    def reset(
        self, position_m: FloatsLike = (0.0, 0.0, 0.0), yaw_rad: float = 0.0, rotors_at_hover: bool = False
    ) -> None:
        self._batch.reset(self.id, position_m, yaw_rad, rotors_at_hover)
