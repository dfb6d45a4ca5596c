"""Ramps: F_ba(k) of (E13) and its derivatives; the rates a rig can run."""

import numpy as np
import pytest

from breakaway.plan.ramps import Ramps, breakaway_measurement
from breakaway.plan.setting import Limits, Setting
from breakaway.quasistatic import breakaway_force, breakaway_velocity

BASE = {"Fc": 1.0, "Fs": 1.5, "V": 5.0, "delta": 1.3, "s": 2.0, "sigma": 0.01}
RATES = np.geomspace(0.01, 100, 9)


def _at(values):
    return {name: np.array([[v]]) for name, v in values.items()}


@pytest.mark.parametrize("F_hat", ["Fc", "Fs", "avg", "self"])
def test_value_and_speed_are_e13_and_e12(F_hat):
    F, speed, _ = breakaway_measurement(RATES, _at(BASE), F_hat, 0.9)
    args = (BASE["Fc"], BASE["Fs"], BASE["V"], BASE["delta"], BASE["s"], BASE["sigma"], F_hat, 0.9)
    np.testing.assert_allclose(F[0], breakaway_force(RATES, *args), rtol=1e-12)
    np.testing.assert_allclose(speed[0], breakaway_velocity(RATES, *args), rtol=1e-12)


@pytest.mark.parametrize("F_hat", ["Fc", "Fs", "avg", "self"])
@pytest.mark.parametrize("name", ["Fc", "Fs", "V", "delta", "s", "sigma"])
def test_derivatives_match_central_differences(F_hat, name):
    _, _, partial = breakaway_measurement(RATES, _at(BASE), F_hat, 0.9)
    step = 1e-6

    def shifted(sign):
        p = dict(BASE)
        p[name] = p[name] * np.exp(sign * step) if name in ("V", "s") else p[name] + sign * step
        return breakaway_force(RATES, p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"],
                               F_hat, 0.9)

    numeric = (shifted(1) - shifted(-1)) / (2 * step)
    np.testing.assert_allclose(partial[name][0], numeric, rtol=2e-5, atol=1e-8)


def test_V_and_s_enter_only_through_their_product():
    _, _, partial = breakaway_measurement(RATES, _at({**BASE, "sigma": 0.0}), "avg", 0.95)
    np.testing.assert_allclose(partial["V"], partial["s"], rtol=1e-12, atol=1e-300)


def test_candidates_keep_the_breakaway_speed_below_v_max_and_yield_only_below_u_max():
    limits = Limits(u_max=1.3, v_max=50.0, v_min=0.1, travel=None, duration=20.0, sample_rate=1e3)
    setting = Setting(limits, noise=0.01, units={"F": "N", "v": "m/s", "k": "N/s"}, grid=40)
    family = Ramps()
    P = _at({**BASE, "n": 1.0})
    cands = family.candidates(P, setting)
    info = family.information(cands, P, setting, ["Fc", "Fs", "V", "delta"])
    assert np.max(info.predicted["speed"]) <= 50.0 * (1 + 1e-12)
    # a ramp that would break away above u_max (or after the run's 20 s) yields nothing
    F_ba = info.predicted["F_ba"]
    ends = np.minimum(1.3, cands.points["k"] * 20.0)
    assert np.all(~info.usable | (F_ba < ends))
    assert np.any(~info.usable) and np.any(info.usable)
    assert np.all(info.matrix[~info.usable] == 0)
