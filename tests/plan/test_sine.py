"""The sine: its information integrated over branches equals the Fisher information of
the sampled record (finite differences of (E6') along it), and its limits hold."""

import numpy as np
import pytest

from breakaway.plan.curve import PARAMETERS
from breakaway.plan.setting import Limits, Setting
from breakaway.plan.sine import Sine, _sine_information, sine_samples
from breakaway.presliding import presliding_force

BASE = {"Fc": 1.0, "Fs": 1.5, "V": 0.05, "delta": 1.0, "s": 100.0, "sigma": 0.5, "n": 1.0}
NAMES = ["Fc", "Fs", "V", "delta", "s", "sigma"]


def _record_information(A, f, duration, rate, noise):
    """Jᵀ·J/σ² of the record sampled at ``rate``, by central differences of (E6')."""
    t = np.arange(0.0, duration, 1.0 / rate)
    x = A * np.sin(2 * np.pi * f * t)

    def force(p):
        return presliding_force(t, x, p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"])

    columns = []
    for name in NAMES:
        up, down = dict(BASE), dict(BASE)
        if name in ("V", "s"):
            up[name] *= np.exp(1e-6)
            down[name] *= np.exp(-1e-6)
        else:
            up[name] += 1e-6
            down[name] -= 1e-6
        columns.append((force(up) - force(down)) / 2e-6)
    J = np.column_stack(columns)
    return J.T @ J / noise**2


# gross sliding past V, a loop inside presliding, and a long stroke at a slow frequency
@pytest.mark.parametrize("A, f", [(0.03, 1.0), (0.004, 2.0), (0.3, 0.5)])
def test_information_matches_the_sampled_record(A, f):
    duration, rate, noise = 3.0, 20000.0, 0.01
    x, v, d, weight = sine_samples(A, f, duration, rate, noise, 1 / BASE["s"], 1 / BASE["s"])
    theta = np.array([[BASE[n] for n in PARAMETERS]])
    columns = np.array([PARAMETERS.index(n) for n in NAMES])
    info = np.zeros((1, 1, len(NAMES), len(NAMES)))
    peak = np.zeros((1, 1))
    with np.errstate(divide="ignore"):
        log_speed = np.log(np.abs(v))
    _sine_information(theta, columns, x[None], v[None], log_speed[None], d[None], weight[None],
                      info, peak)
    reference = _record_information(A, f, duration, rate, noise)
    se = np.sqrt(np.diag(np.linalg.inv(info[0, 0])))
    se_reference = np.sqrt(np.diag(np.linalg.inv(reference)))
    np.testing.assert_allclose(se, se_reference, rtol=0.1)
    t = np.arange(0.0, duration, 1.0 / rate)
    F = presliding_force(t, A * np.sin(2 * np.pi * f * t), *(BASE[n] for n in
                         ("Fc", "Fs", "V", "delta", "s", "sigma")))
    assert peak[0, 0] == pytest.approx(np.max(np.abs(F)), rel=1e-3)


def test_candidates_respect_travel_speed_and_force():
    limits = Limits(u_max=1.45, v_max=0.2, v_min=1e-3, travel=0.1, duration=10.0,
                    sample_rate=500.0)
    setting = Setting(limits, noise=0.01, units={"F": "N", "v": "m/s", "x": "m"}, grid=64)
    P = {name: np.array([[v]]) for name, v in BASE.items()}
    family = Sine()
    cands = family.candidates(P, setting)
    A, f = cands.points["amplitude"], cands.points["frequency"]
    assert A.max() <= 0.05 + 1e-15
    assert np.all(2 * np.pi * f * A <= 0.2 * (1 + 1e-12))
    assert f.min() >= 2 / 10.0 and f.max() <= 500.0 / 20
    info = family.information(cands, P, setting, NAMES)
    # the loops that reach Fs = 1.5 > u_max are not run; those that stay below are
    peak = info.predicted["peak_force"][0]
    np.testing.assert_array_equal(info.usable[0], peak <= 1.45)
    assert info.usable.any() and not info.usable.all()
