"""One physics step of every drone in a batch, as a fixed sequence of numpy passes, and the rows it uses.

A batch keeps one float64 array of shape (ROWS, n), a column per drone: the dynamics state
(rows 0-17, see sim.quadrotor.dynamics), the rate loop's state, and the held command. A step is
QuadrotorSim.step for every column: the rate loop and RK4 as numpy passes that mirror the scalar
code operation for operation, and the ground contact through the scalar code itself, for the
drones in contact only.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from sim.quadrotor.dynamics import (
    FLAT_TO_ROWS,
    ONES_ROW,
    POS,
    QUAT,
    RATES,
    STATE_ROWS,
    RigidBodyModel,
    bind_rk4,
    normalize_quaternions,
)
from sim.quadrotor.ground import GroundContact
from sim.quadrotor.params import QuadrotorParams
from sim.quadrotor.rate_control import RateGains, bind_rate_loop
from sim.types import FloatArray

IndexArray = npt.NDArray[np.intp]

FILTERED, FILTERED_DOT, INTEGRAL, RATE_STATE = slice(18, 21), slice(21, 24), slice(24, 27), slice(18, 27)
RATES_CMD, SHARES_AND_BASE, BASE, MOTOR_CMD = slice(27, 30), slice(30, 34), 33, slice(34, 38)
ROWS = 38
"""Rows 30-32 are the rate loop's scratch, next to the thrust share (33) it sums them with."""
_PZ = POS.stop - 1
_FLAT_ROWS = np.array(FLAT_TO_ROWS, dtype=np.intp)
FEW_IN_CONTACT = 6
"""Up to this many drones in contact go through the scalar GroundContact.apply one by one; more
through its column form, whose fixed cost in numpy calls is larger and whose cost per drone smaller."""


class StepKernel:
    """Buffers and bound numpy passes for one batch size; made again when a drone joins or leaves.

    step(noise, motor_cols, frozen_cols) advances every column of floats by one physics step:
    rate loop and mixer (motor_cols take their motor command instead and their rate loop holds
    still), RK4, renormalise, rate clamp, ground contact, then commits. Columns whose new state is
    not finite, and frozen_cols, keep their previous state; it returns the former.
    """

    def __init__(
        self, floats: FloatArray, on_ground: npt.NDArray[np.bool_], p: QuadrotorParams, dt_s: float
    ) -> None:
        n = floats.shape[1]
        state = floats[:STATE_ROWS]
        out = np.empty((STATE_ROWS, n))
        out[ONES_ROW] = 1.0
        rotor_cmd = np.empty((4, n))
        rate_loop = bind_rate_loop(
            RateGains(p, dt_s),
            dt_s,
            state[RATES],
            floats[FILTERED],
            floats[FILTERED_DOT],
            floats[INTEGRAL],
            floats[RATES_CMD],
            floats[SHARES_AND_BASE],
            rotor_cmd,
        )
        rk4 = bind_rk4(RigidBodyModel(p), dt_s, state, out)
        ground = GroundContact(p, dt_s)
        out_quat, out_rates, out_z = out[QUAT], out[RATES], out[_PZ]
        norm, squares, finite = np.empty(n), np.empty((4, n)), np.empty((STATE_ROWS, n), dtype=bool)
        top, bottom = np.array(p.max_body_rate_rad_s), np.array(-p.max_body_rate_rad_s)
        rate_state, integral, motor_cmd = floats[RATE_STATE], floats[INTEGRAL], floats[MOTOR_CMD]
        lowest, all_true, isfinite = np.minimum.reduce, np.logical_and.reduce, np.isfinite
        no_columns = np.empty(0, dtype=np.intp)

        def step(noise: FloatArray, motor_cols: IndexArray, frozen_cols: IndexArray) -> IndexArray:
            if motor_cols.size:
                held = rate_state[:, motor_cols]
            rate_loop()
            if motor_cols.size:
                rate_state[:, motor_cols] = held
                rotor_cmd[:, motor_cols] = motor_cmd[:, motor_cols]
            rk4(rotor_cmd, noise)
            normalize_quaternions(out_quat, norm, squares)
            # The model has no rotational drag: the clamp keeps |w| dt far inside RK4's stability region.
            np.maximum(out_rates, bottom, out=out_rates)
            np.minimum(out_rates, top, out=out_rates)
            if lowest(out_z) <= 0.0:
                contact = out_z <= 0.0
                resting = touch_ground(out, np.flatnonzero(contact))
                # A flight controller's land detector zeroes the integral while landed.
                integral[:, resting] = 0.0
            else:
                contact = None
            isfinite(out, finite)
            bad = no_columns if all_true(finite, None) else np.flatnonzero(~finite.all(axis=0))
            keep = np.union1d(bad, frozen_cols) if bad.size or frozen_cols.size else no_columns
            if keep.size:
                out[:, keep] = state[:, keep]
                if contact is not None:
                    contact[keep] = on_ground[keep]
            np.copyto(state, out)
            if contact is None:
                on_ground.fill(False)
            else:
                np.copyto(on_ground, contact)
            return bad

        def touch_ground(out: FloatArray, cols: IndexArray) -> IndexArray:
            """GroundContact on the drones in contact (cols); returns those resting."""
            if cols.size > FEW_IN_CONTACT:
                block = out[:, cols]
                resting_mask = ground.apply_columns(block)
                out[:, cols] = block
                return cols[resting_mask]
            rows = np.ix_(_FLAT_ROWS, cols)
            drones = out[rows].T.tolist()  # each drone's flat state, as QuadrotorSim keeps it
            resting = [col for col, s in zip(cols.tolist(), drones, strict=True) if ground.apply(s)[1]]
            out[rows] = np.array(drones).T
            return np.array(resting, dtype=np.intp)

        self.step = step
