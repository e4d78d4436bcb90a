"""Quadrotor simulators: FlightGoggles-like rotor physics and the lab's kinematic simple_sim.

QuadrotorSim and SimpleSim step one drone in plain floats (what a world's nodes use);
QuadrotorBatch and SimpleSimBatch step many drones together in one numpy pass per step, each
drone bit for bit as the single sim with the same seed and commands would.
"""

from sim.quadrotor.batch import Drone, QuadrotorBatch
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rotation import euler_sxyz_to_quat, quat_to_euler_sxyz, quat_to_matrix
from sim.quadrotor.sim import QuadrotorSim
from sim.quadrotor.simple_batch import SimpleDrone, SimpleSimBatch
from sim.quadrotor.simple_sim import GpsReading, SimpleSim, SimpleSimParams, SimpleSimState
from sim.quadrotor.slots import DroneRemovedError
from sim.quadrotor.state import Command, MotorSpeedCommand, QuadrotorState, RateThrustCommand

__all__ = [
    "Command",
    "Drone",
    "DroneRemovedError",
    "GpsReading",
    "MotorSpeedCommand",
    "QuadrotorBatch",
    "QuadrotorParams",
    "QuadrotorSim",
    "QuadrotorState",
    "RateThrustCommand",
    "SimpleDrone",
    "SimpleSim",
    "SimpleSimBatch",
    "SimpleSimParams",
    "SimpleSimState",
    "euler_sxyz_to_quat",
    "quat_to_euler_sxyz",
    "quat_to_matrix",
]
