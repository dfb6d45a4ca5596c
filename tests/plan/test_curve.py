"""The steady curve's magnitude and its derivatives in the planner's coordinates."""

import numpy as np
import pytest

from breakaway.plan.curve import magnitude
from breakaway.steady import stribeck_magnitude

BASE = {"Fc": 1.0, "Fs": 1.5, "V": 0.05, "delta": 1.3, "sigma": 0.4, "n": 0.7}
SPEEDS = np.array([0.0, 1e-4, 0.01, 0.05, 0.2, 3.0])


def _at(values):
    return {name: np.array([[v]]) for name, v in values.items()}


def test_value_is_the_stribeck_curve_plus_the_viscous_power():
    value, _, _ = magnitude(SPEEDS, _at(BASE))
    expected = stribeck_magnitude(SPEEDS, 1.0, 1.5, 0.05, 1.3) + 0.4 * SPEEDS**0.7
    np.testing.assert_allclose(value[0], expected, rtol=1e-13)
    assert value[0, 0] == pytest.approx(1.5)  # g(0) = Fs


@pytest.mark.parametrize("name", ["Fc", "Fs", "V", "delta", "sigma", "n"])
def test_partials_match_central_differences(name):
    _, _, partial = magnitude(SPEEDS, _at(BASE))
    step = 1e-6

    def shifted(sign):
        p = dict(BASE)
        p[name] = p[name] * np.exp(sign * step) if name == "V" else p[name] + sign * step
        return magnitude(SPEEDS, _at(p))[0][0]

    numeric = (shifted(1) - shifted(-1)) / (2 * step)
    np.testing.assert_allclose(partial[name][0], numeric, rtol=1e-6, atol=1e-9)


def test_slope_matches_central_differences():
    v = SPEEDS[1:]
    _, slope, _ = magnitude(v, _at(BASE))
    h = 1e-7 * v
    numeric = (magnitude(v + h, _at(BASE))[0] - magnitude(v - h, _at(BASE))[0]) / (2 * h)
    np.testing.assert_allclose(slope[0], numeric[0], rtol=1e-5)
