"""/uav/input/velocity straight from a student (no position controller): the drone flies at that velocity."""

from __future__ import annotations

import numpy as np
import pytest

from .conftest import FLY_NO_NOISE, make_lab, node, start

COMMAND_M_S = (1.0, -0.5, 0.5)


@pytest.mark.parametrize("noise", [True, False])
def test_velocity_setpoint_without_position_controller_moves_at_that_velocity(noise: bool) -> None:
    lab = make_lab("fly" if noise else FLY_NO_NOISE)
    probe = start(lab)
    lab.executor.spin_until(6.0)  # hovering at (0, 0, 3)
    node(lab, "position_controller_node").destroy_node()
    lab.publish("/uav/input/velocity", dict(zip("xyz", COMMAND_M_S, strict=True)), None)
    lab.executor.spin_until(14.0)

    publishers = {p.node.get_name() for p in lab.bus.get_topic("/uav/input/velocity").publishers}
    assert publishers == {"_rest_api"}
    assert len(probe.got["/uav/input/velocity"]) == 300 + 1  # 50 Hz for 6 s, then the one command
    v = probe.velocities(after_s=9.0)[:, 1:]
    assert np.abs(v.mean(axis=0) - COMMAND_M_S).max() < 0.05
    assert np.abs(v - COMMAND_M_S).max() < 0.15
    p0, p1 = probe.positions(after_s=9.0)[[0, -1]]
    travelled_m_s = (p1[1:] - p0[1:]) / (p1[0] - p0[0])
    assert np.abs(travelled_m_s - COMMAND_M_S).max() < 0.05
