"""Pure controllers: the lab PID, the lab's position controller, and the retuned cascade."""

from sim.control.cascade import (
    AngleController,
    AngleGains,
    AttitudeThrustSetpoint,
    PositionController,
    PositionGains,
    VelocityController,
    VelocityGains,
)
from sim.control.closed_loop import Cascade, CascadeGains, ClosedLoop
from sim.control.lab_position import LAB_PID_DT_S, LabPositionController
from sim.control.pid import PID
from sim.control.simple_loop import SimpleModeLoop

__all__ = [
    "LAB_PID_DT_S",
    "PID",
    "AngleController",
    "AngleGains",
    "AttitudeThrustSetpoint",
    "Cascade",
    "CascadeGains",
    "ClosedLoop",
    "LabPositionController",
    "PositionController",
    "PositionGains",
    "SimpleModeLoop",
    "VelocityController",
    "VelocityGains",
]
