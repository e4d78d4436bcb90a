"""Quadrotor simulators: FlightGoggles-like rotor physics and the lab's kinematic simple_sim."""

from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rotation import euler_sxyz_to_quat, quat_to_euler_sxyz, quat_to_matrix
from sim.quadrotor.sim import QuadrotorSim
from sim.quadrotor.simple_sim import GpsReading, SimpleSim, SimpleSimParams, SimpleSimState
from sim.quadrotor.state import Command, MotorSpeedCommand, QuadrotorState, RateThrustCommand

__all__ = [
    "Command",
    "GpsReading",
    "MotorSpeedCommand",
    "QuadrotorParams",
    "QuadrotorSim",
    "QuadrotorState",
    "RateThrustCommand",
    "SimpleSim",
    "SimpleSimParams",
    "SimpleSimState",
    "euler_sxyz_to_quat",
    "quat_to_euler_sxyz",
    "quat_to_matrix",
]
