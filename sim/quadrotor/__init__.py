"""Quadrotor simulators: FlightGoggles-like rotor physics and the lab's kinematic simple_sim."""

from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rotation import euler_sxyz_to_quat, quat_to_euler_sxyz, quat_to_matrix
from sim.quadrotor.sim import QuadrotorSim
from sim.quadrotor.state import Command, MotorSpeedCommand, QuadrotorState, RateThrustCommand

__all__ = [
    "Command",
    "MotorSpeedCommand",
    "QuadrotorParams",
    "QuadrotorSim",
    "QuadrotorState",
    "RateThrustCommand",
    "euler_sxyz_to_quat",
    "quat_to_euler_sxyz",
    "quat_to_matrix",
]
