"""pressure_node (ref §3.6): /uav/sensors/gps altitude → /uav/sensors/pressure (mbar) at 10 Hz."""

from __future__ import annotations

import numpy as np
import pytest

from server.packages.sensor_simulation.pressure import pressure_mbar

from .conftest import GROUNDED_SENSORS, Flight, make_lab, start

PRESSURE = "/uav/sensors/pressure"


@pytest.mark.parametrize(
    ("altitude_m", "expected_mbar"), [(0.0, 1013.250), (3.0, 1012.889), (10.0, 1012.049)]
)
def test_pressure_formula_at_the_labs_altitudes_matches_its_values(
    altitude_m: float, expected_mbar: float
) -> None:
    assert pressure_mbar(altitude_m) == pytest.approx(expected_mbar, abs=1e-3)


def test_pressure_formula_decreases_with_altitude_over_the_arena() -> None:
    p = np.array([pressure_mbar(h) for h in np.linspace(0.0, 15.0, 301)])
    assert np.all(np.diff(p) < 0.0)
    assert (p[0] - p[-1]) / 15.0 == pytest.approx(0.12, rel=0.05)  # about 0.12 mbar per metre near the ground


def test_pressure_node_on_the_ground_first_message_0_then_1013_250_mbar_at_10hz() -> None:
    lab = make_lab(GROUNDED_SENSORS)
    probe = start(lab)
    lab.executor.spin_until(5.0)
    got = probe.got[PRESSURE]
    assert got[0] == (pytest.approx(0.1), got[0][1]) and got[0][1].data == 0.0
    values = np.array([m.data for _, m in got[1:]])
    assert len(got) == 50
    assert np.abs(values - 1013.250).max() < 1e-3
    assert np.std(values) < 1e-5  # only the U(-1e-5, 1e-5) noise on a still drone


def test_pressure_node_in_flight_follows_altitude(fly_flight: Flight) -> None:
    probe = fly_flight.probe
    hover = np.array([m.data for t, m in probe.got[PRESSURE] if 8.0 <= t <= 15.0])
    high = np.array([m.data for t, m in probe.got[PRESSURE] if 25.0 <= t <= 30.0])
    assert hover.mean() == pytest.approx(1012.889, abs=2e-3)
    assert high.mean() == pytest.approx(1012.049, abs=2e-3)
    # Each value is the previous tick's altitude, converted: compare with the GPS 0.1 s earlier.
    gps = probe.positions()
    for t, msg in probe.got[PRESSURE][1:]:
        z = gps[np.argmin(np.abs(gps[:, 0] - (t - 0.1))), 3]
        assert msg.data == pytest.approx(pressure_mbar(z), abs=5e-3)
