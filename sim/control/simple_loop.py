"""The lab's simple mode without ROS: SimpleSim at 20 Hz under the lab position PID at 100 Hz.

The controller acts on the latest GPS reading, as the node does; its timer may start late
(the lab's node sleeps 5 s first) and until then the velocity command stays zero.
"""

from __future__ import annotations

from sim.control.lab_position import LAB_PID_DT_S, LabPositionController
from sim.quadrotor.simple_sim import SimpleSim, SimpleSimState
from sim.types import FloatsLike


class SimpleModeLoop:
    """Interleaves controller ticks (every controller_period_s) with the sim's own ticks."""

    def __init__(
        self,
        sim: SimpleSim,
        controller: LabPositionController | None = None,
        *,
        controller_period_s: float = LAB_PID_DT_S,
        controller_start_s: float = 0.0,
    ) -> None:
        if not controller_period_s > 0 or not controller_start_s >= 0:
            raise ValueError("controller_period_s must be > 0 and controller_start_s >= 0")
        self.sim = sim
        self.controller = controller if controller is not None else LabPositionController()
        self.controller_period_s = controller_period_s
        self._start_tick = round(controller_start_s / controller_period_s)
        self._tick = 0

    @property
    def time_s(self) -> float:
        return self._tick * self.controller_period_s

    def set_setpoint(self, position_m: FloatsLike) -> None:
        """A /uav/input/position message."""
        self.controller.set_setpoint(position_m)

    def run(self, duration_s: float) -> list[SimpleSimState]:
        """Run for duration_s; returns the true state after every sim tick."""
        states: list[SimpleSimState] = []
        for _ in range(round(duration_s / self.controller_period_s)):
            if self._tick >= self._start_tick:
                # The lab PID always integrates with dt = 0.01 s, whatever the timer period.
                self.sim.set_velocity_command(self.controller.update(self.sim.gps.position_m, LAB_PID_DT_S))
            if self.sim.advance(self.controller_period_s):
                states.append(self.sim.state)
            self._tick += 1
        return states
