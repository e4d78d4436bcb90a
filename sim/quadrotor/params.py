"""Physical and inner-loop parameters of the simulated quadrotor."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields


@dataclass(frozen=True)
class QuadrotorParams:
    """The FlightGoggles drone (`drone.yaml` + dynamics-node defaults, lab reference §4).

    Frames: world z up, body x forward, y left, z up. Motor 1 is front-left and motors
    are numbered counter-clockwise seen from above; rotors sit at (±l, ±l) in the body frame.
    """

    mass_kg: float = 1.0
    arm_length_m: float = 0.08
    """Moment arm: distance of each rotor from the body x and y axes."""
    inertia_kg_m2: tuple[float, float, float] = (0.0049, 0.0049, 0.0069)
    """Principal moments of inertia (Ixx, Iyy, Izz)."""
    thrust_coeff_n_per_rad_s2: float = 1.91e-6
    """k_T: rotor thrust = k_T * omega^2, N/(rad/s)^2."""
    torque_coeff_nm_per_rad_s2: float = 2.6e-7
    """k_Q: rotor reaction torque = k_Q * omega^2, N*m/(rad/s)^2."""
    motor_time_constant_s: float = 0.02
    max_rotor_speed_rad_s: float = 2200.0
    drag_coeff_n_per_m_s2: float = 0.1
    """Quadratic body drag: F = -c * |v| * v, N/(m/s)^2."""
    gravity_m_s2: float = 9.81
    angular_process_noise_rad2_s3: float = 0.00025
    """Angular-acceleration noise intensity: per-step std = sqrt(value / dt)."""
    linear_process_noise_m2_s3: float = 0.0005
    """Linear-acceleration noise intensity: per-step std = sqrt(value / dt)."""
    rate_kp_1_s: float = 9.0
    """Inner body-rate loop: alpha_cmd = kp*e + ki*int(e) - kd*d(omega_f)/dt."""
    rate_ki_1_s2: float = 3.0
    rate_kd: float = 0.3
    rate_integral_limit_rad: float = 1000.0
    rate_filter_enabled: bool = True
    """Second-order low-pass on the measured body rates, as FlightGoggles does."""
    rate_filter_cutoff_hz: float = 30.0
    """FlightGoggles' gains P=35530.58 1/s^2, Q=266.57 1/s are a 30 Hz Butterworth."""
    rate_filter_damping: float = math.sqrt(0.5)
    max_rate_command_rad_s: float = 10.0
    """Body-rate commands are clamped to this magnitude per axis (not in FlightGoggles)."""
    max_body_rate_rad_s: float = 60.0
    """Body rates are clamped per axis after each step (not in FlightGoggles). The model has no
    rotational drag, so differential motor commands could spin it up without bound; real frames
    top out near 35 rad/s, and the clamp keeps |w| dt far inside RK4's stability region."""
    gyroscopic_enabled: bool = True
    """Include -omega x (I omega) in the rigid-body equation (FlightGoggles omits it)."""
    ground_friction_coeff: float = 0.5
    """Coulomb friction coefficient between the landed drone and the ground."""
    ground_level_time_constant_s: float = 0.05
    """How fast a landed drone settles level on its legs."""

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, bool):
                continue
            values = value if isinstance(value, tuple) else (value,)
            ok = _positive if f.name not in _MAY_BE_ZERO else _non_negative
            if len(values) not in (1, 3) or not all(ok(v) for v in values):
                raise ValueError(f"QuadrotorParams.{f.name} must be positive and finite, got {value!r}")

    @property
    def hover_rotor_speed_rad_s(self) -> float:
        """Rotor speed at which four rotors carry the weight: sqrt(m g / (4 k_T))."""
        return math.sqrt(self.mass_kg * self.gravity_m_s2 / (4.0 * self.thrust_coeff_n_per_rad_s2))

    @property
    def max_thrust_n(self) -> float:
        """Collective thrust with all rotors at full speed: 4 k_T omega_max^2."""
        return 4.0 * self.thrust_coeff_n_per_rad_s2 * self.max_rotor_speed_rad_s**2


# Gains and noise intensities may be switched off; physical quantities may not.
_MAY_BE_ZERO = frozenset(
    {
        "rate_ki_1_s2",
        "rate_kd",
        "angular_process_noise_rad2_s3",
        "linear_process_noise_m2_s3",
        "drag_coeff_n_per_m_s2",
        "ground_friction_coeff",
    }
)


def _non_negative(value: object) -> bool:
    return isinstance(value, (int, float)) and math.isfinite(value) and value >= 0


def _positive(value: object) -> bool:
    return _non_negative(value) and value > 0  # type: ignore[operator]
