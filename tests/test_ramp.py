"""breakaway.ramp: z along a simulated run (E5)."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.ramp import presliding_z


def z_by_loop(x, v, s):
    """The definition sample by sample: x_r is x where ẋ last changed sign."""
    x_r, last, previous = np.zeros_like(x), 0.0, 0.0
    for i, direction in enumerate(np.sign(v)):
        if direction != 0 and previous != 0 and direction != previous:
            last = x[i]
        if direction != 0:
            previous = direction
        x_r[i] = last
    return s * np.abs(x - x_r)


def test_a_hand_worked_run():
    x = np.array([0.0, 1.0, 2.0, 2.0, 1.5, 1.0, 1.2, 1.4])
    v = np.array([0.0, 1.0, 1.0, 0.0, -1.0, -1.0, 1.0, 1.0])
    # from rest x_r = 0; ẋ turns negative at x = 1.5, positive again at x = 1.2
    expected = 2.0 * np.abs(x - np.array([0, 0, 0, 0, 1.5, 1.5, 1.2, 1.2]))
    np.testing.assert_array_equal(presliding_z(x, v, 2.0), expected)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_equals_the_sample_by_sample_definition(seed):
    rng = np.random.default_rng(seed)
    n = 5000
    # runs of each direction with standstills (ẋ = 0) between and inside them
    v = np.repeat(rng.choice([-1.0, 0.0, 1.0], size=n // 25, p=[0.4, 0.2, 0.4]), 25)
    v *= rng.uniform(0.5, 2.0, v.size)
    x = np.cumsum(v) * 1e-4
    np.testing.assert_array_equal(presliding_z(x, v, 3000.0), z_by_loop(x, v, 3000.0))


def test_no_motion_and_no_samples():
    x = np.linspace(0, 1, 4)
    np.testing.assert_array_equal(presliding_z(x, np.zeros(4), 1.0), x)
    assert presliding_z(np.array([]), np.array([]), 1.0).size == 0
