"""The programme a rig runs: its columns, units, rows and limits."""

import io

import numpy as np
import pytest

from breakaway.plan.programme import RAMP_ROWS, ramps_csv, setpoints_csv, sine_csv

ROTARY = {"F": "N·m", "x": "rad", "v": "rad/s", "t": "s", "k": "N·m/s"}


def _table(text):
    lines = [line for line in text.splitlines() if not line.startswith("#")]
    return lines[0], np.loadtxt(io.StringIO("\n".join(lines[1:])), delimiter=",", ndmin=2)


def test_ramps_rise_at_their_rate_to_their_end_force_in_rotary_units():
    text = ramps_csv([0.5, 2.0], [3.0, 2.5], ROTARY)
    assert "u [N·m]" in text and "t [s]" in text
    header, table = _table(text)
    assert header == "run,t,u"
    assert table.shape == (2 * RAMP_ROWS, 3)
    for run, k, end in ((1, 0.5, 3.0), (2, 2.0, 2.5)):
        rows = table[table[:, 0] == run]
        np.testing.assert_allclose(rows[:, 2], k * rows[:, 1], rtol=1e-7)
        assert rows[0, 2] == 0 and rows[-1, 2] == pytest.approx(end)


def test_setpoints_hold_each_speed_both_ways():
    header, table = _table(setpoints_csv([0.1, 0.02], ROTARY))
    assert header == "run,v"
    np.testing.assert_allclose(table, [[1, 0.1], [1, -0.1], [2, 0.02], [2, -0.02]])
    assert "v [rad/s]" in setpoints_csv([0.1], ROTARY)


def test_the_sine_is_the_position_reference_from_rest():
    text = sine_csv(0.01, 2.0, 3.0, 1000.0, ROTARY)
    header, table = _table(text)
    assert header == "t,x" and "x [rad]" in text
    np.testing.assert_allclose(table[:, 1], 0.01 * np.sin(2 * np.pi * 2.0 * table[:, 0]),
                               atol=1e-9)
    assert table[0, 0] == 0 and table[-1, 0] == pytest.approx(3.0)
    assert np.max(np.abs(table[:, 1])) <= 0.01
