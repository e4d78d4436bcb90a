"""The 2022 lab's controller cascade, retuned: position -> velocity -> angle -> rateThrust.

Each controller keeps its latest setpoint (as the ROS node keeps the latest message) and
is ticked with update(..., dt_s) at its own rate. Angles are Euler 'sxyz' (rad), world
frame z up, body x forward / y left. See docs/physics.md for the gains and why.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from sim.control.pid import PID
from sim.quadrotor.rotation import wrap_angle
from sim.quadrotor.state import RateThrustCommand, as_finite_floats
from sim.types import FloatsLike

DEFAULT_POSITION_SETPOINT_M = (0.0, 0.0, 3.0)


@dataclass(frozen=True)
class PositionGains:
    """Position error (m) -> velocity setpoint (m/s), then speed limits."""

    kp_xy_1_s: float = 0.8
    kp_z_1_s: float = 1.0
    max_speed_xy_m_s: float = 4.0
    """Limit on the horizontal speed (norm of x, y), keeping the direction."""
    max_speed_z_m_s: float = 3.0


@dataclass(frozen=True)
class VelocityGains:
    """Velocity error (m/s) -> acceleration command (m/s^2) -> tilt and thrust.

    The kd terms act on the measured acceleration (the derivative of the measured velocity),
    not on the error, so a step in the velocity setpoint causes no kick.
    """

    kp_xy_1_s: float = 2.5
    ki_xy_1_s2: float = 0.0
    kd_xy_s: float = 0.3
    kp_z_1_s: float = 4.0
    ki_z_1_s2: float = 0.3
    kd_z_s: float = 0.0
    max_integral_accel_m_s2: float = 4.0
    integral_band_m_s: float = 0.05
    """The z integral integrates only while the measured vertical speed is within this band (m/s):
    a steady bias (a heavier drone, rotor noise) shows at rest; climbs and their approach do not."""
    """Anti-windup: bound on the integral term's contribution |ki * I| per axis (m/s^2)."""
    min_thrust_n: float = 0.0
    max_thrust_n: float = 20.0
    """The lab clamps thrust to [0, 20] N."""


@dataclass(frozen=True)
class AngleGains:
    """Euler-angle error (rad) -> body-rate command (rad/s)."""

    kp_roll_pitch_1_s: float = 3.0
    kp_yaw_1_s: float = 2.0
    max_tilt_rad: float = 0.5
    """Roll and pitch setpoints are clamped to +-this, as in the lab."""


@dataclass(frozen=True)
class AttitudeThrustSetpoint:
    """Output of the velocity controller: /uav/input/attitude (rad) and /uav/input/thrust (N)."""

    roll_rad: float
    pitch_rad: float
    yaw_rad: float
    thrust_n: float


class PositionController:
    """P control on position with separate horizontal and vertical speed limits."""

    def __init__(
        self, gains: PositionGains | None = None, setpoint_m: FloatsLike = DEFAULT_POSITION_SETPOINT_M
    ):
        self.gains = gains if gains is not None else PositionGains()
        self.setpoint_m = as_finite_floats("setpoint_m", setpoint_m, 3)

    def set_setpoint(self, setpoint_m: FloatsLike) -> None:
        self.setpoint_m = as_finite_floats("setpoint_m", setpoint_m, 3)

    def update(self, measured_position_m: FloatsLike, dt_s: float) -> tuple[float, float, float]:
        """Velocity setpoint (m/s, world). dt_s is unused by a P law but kept for a uniform API."""
        g = self.gains
        px, py, pz = as_finite_floats("measured_position_m", measured_position_m, 3)
        sx, sy, sz = self.setpoint_m
        vx, vy = g.kp_xy_1_s * (sx - px), g.kp_xy_1_s * (sy - py)
        speed = math.hypot(vx, vy)
        if speed > g.max_speed_xy_m_s:
            vx, vy = vx * g.max_speed_xy_m_s / speed, vy * g.max_speed_xy_m_s / speed
        vz = min(max(g.kp_z_1_s * (sz - pz), -g.max_speed_z_m_s), g.max_speed_z_m_s)
        return vx, vy, vz


class VelocityController:
    """PI on world velocity -> desired acceleration -> roll/pitch setpoint and collective thrust.

    The tilt points the thrust along the desired acceleration plus gravity, rotated into the
    heading frame; at yaw 0 and small angles this is the lab's corrected sign chain
    roll_sp = -u_y, pitch_sp = +u_x (with u = a/g). Thrust is m(g + a_z) divided by the measured
    tilt cosine, so climbing rate does not sag while the vehicle leans. The vehicle's known
    quadratic drag at the setpoint velocity is fed forward, so steady flight needs no integral.
    """

    def __init__(
        self,
        mass_kg: float,
        gravity_m_s2: float = 9.81,
        gains: VelocityGains | None = None,
        drag_coeff_n_per_m_s2: float = 0.0,
    ):
        self.gains = gains if gains is not None else VelocityGains()
        self.mass_kg, self.gravity_m_s2 = mass_kg, gravity_m_s2
        self.drag_per_mass = drag_coeff_n_per_m_s2 / mass_kg
        g = self.gains
        self.pids = tuple(
            PID(kp, ki, integral_limit=g.max_integral_accel_m_s2 / ki if ki > 0 else None)
            for kp, ki in (
                (g.kp_xy_1_s, g.ki_xy_1_s2),
                (g.kp_xy_1_s, g.ki_xy_1_s2),
                (g.kp_z_1_s, g.ki_z_1_s2),
            )
        )
        self.setpoint_m_s: tuple[float, ...] = (0.0, 0.0, 0.0)
        self.yaw_setpoint_rad = 0.0
        self._prev_velocity: tuple[float, ...] | None = None  # for the acceleration (kd) term

    def set_setpoint(self, velocity_m_s: FloatsLike, yaw_rad: float = 0.0) -> None:
        self.setpoint_m_s = as_finite_floats("velocity_m_s", velocity_m_s, 3)
        (self.yaw_setpoint_rad,) = as_finite_floats("yaw_rad", (yaw_rad,), 1)

    def update(
        self, measured_velocity_m_s: FloatsLike, measured_euler_rad: FloatsLike, dt_s: float
    ) -> AttitudeThrustSetpoint:
        measured = as_finite_floats("measured_velocity_m_s", measured_velocity_m_s, 3)
        roll, pitch, yaw = as_finite_floats("measured_euler_rad", measured_euler_rad, 3)
        ax, ay, az = (
            pid.update(sp, m, dt_s) for pid, sp, m in zip(self.pids, self.setpoint_m_s, measured, strict=True)
        )
        prev = self._prev_velocity if self._prev_velocity is not None else measured
        self._prev_velocity = measured
        kd_xy, kd_z = self.gains.kd_xy_s / dt_s, self.gains.kd_z_s / dt_s
        sx, sy, sz = self.setpoint_m_s
        drag = self.drag_per_mass * math.sqrt(sx * sx + sy * sy + sz * sz)
        ax += drag * sx - kd_xy * (measured[0] - prev[0])
        ay += drag * sy - kd_xy * (measured[1] - prev[1])
        az += drag * sz - kd_z * (measured[2] - prev[2])
        g = self.gravity_m_s2
        # Specific force to produce, in the heading frame (x forward, y left, z up).
        c, s = math.cos(yaw), math.sin(yaw)
        fx, fy = c * ax + s * ay, -s * ax + c * ay
        fz = max(g + az, 0.2 * g)  # never ask to point the thrust downwards
        pitch_sp = math.atan2(fx, fz)
        roll_sp = math.atan2(-fy, math.hypot(fx, fz))
        tilt_cos = max(math.cos(roll) * math.cos(pitch), 0.5)
        raw_thrust = self.mass_kg * max(g + az, 0.0) / tilt_cos
        thrust = min(max(raw_thrust, self.gains.min_thrust_n), self.gains.max_thrust_n)
        self._stop_windup(raw_thrust, thrust, g + az, sz - measured[2], measured[2], dt_s)
        return AttitudeThrustSetpoint(roll_sp, pitch_sp, self.yaw_setpoint_rad, thrust)

    def _stop_windup(
        self,
        raw_thrust: float,
        thrust: float,
        lift_m_s2: float,
        error_z: float,
        measured_vz: float,
        dt_s: float,
    ) -> None:
        """Conditional integration: take back this tick's z integration while thrust is pinned at a
        limit (or asked to be negative) and the error pushes further into it, and while the drone
        climbs or sinks (vertical speed beyond a small band), where the loop's lag would otherwise
        be integrated as if it were a steady bias. The integral is there for steady model mismatch; left to
        integrate transients it holds the drone off its altitude for many seconds afterwards."""
        pushing_up = raw_thrust > thrust and error_z > 0
        pushing_down = (raw_thrust < thrust or lift_m_s2 <= 0.0) and error_z < 0
        transient = abs(measured_vz) > self.gains.integral_band_m_s
        if pushing_up or pushing_down or transient:
            self.pids[2].integral -= error_z * dt_s


class AngleController:
    """P control on Euler angles, converted from Euler-angle rates to body rates."""

    def __init__(self, gains: AngleGains | None = None):
        self.gains = gains if gains is not None else AngleGains()
        self.setpoint = AttitudeThrustSetpoint(0.0, 0.0, 0.0, 0.0)

    def set_setpoint(self, setpoint: AttitudeThrustSetpoint) -> None:
        self.setpoint = setpoint

    def update(self, measured_euler_rad: FloatsLike, dt_s: float) -> RateThrustCommand:
        """The rateThrust command for the measured attitude (dt_s unused by a P law)."""
        g, sp = self.gains, self.setpoint
        roll, pitch, yaw = as_finite_floats("measured_euler_rad", measured_euler_rad, 3)
        tilt = g.max_tilt_rad
        roll_sp = min(max(sp.roll_rad, -tilt), tilt)
        pitch_sp = min(max(sp.pitch_rad, -tilt), tilt)
        roll_dot = g.kp_roll_pitch_1_s * (roll_sp - roll)
        pitch_dot = g.kp_roll_pitch_1_s * (pitch_sp - pitch)
        yaw_dot = g.kp_yaw_1_s * wrap_angle(sp.yaw_rad - yaw)
        # Euler-angle rates -> body rates for R = Rz(yaw) Ry(pitch) Rx(roll).
        sr, cr = math.sin(roll), math.cos(roll)
        sp_, cp = math.sin(pitch), math.cos(pitch)
        p = roll_dot - sp_ * yaw_dot
        q = cr * pitch_dot + sr * cp * yaw_dot
        r = -sr * pitch_dot + cr * cp * yaw_dot
        return RateThrustCommand((p, q, r), sp.thrust_n)
