"""Forward models with effects: each effect at its neutral value gives back the base
model, and the base model of each kind is the model core's function."""

from __future__ import annotations

import math

import numpy as np
import pytest

from breakaway.identify.effects import lag_filter, play_operator
from breakaway.identify.models import problem_for as Problem
from breakaway.identify.synthetic import BASE_TRUTH, make_dataset
from breakaway.presliding import presliding_force
from breakaway.quasistatic import breakaway_force, presliding_velocity
from breakaway.steady import steady_state_force


@pytest.fixture(scope="module")
def series():
    data, _ = make_dataset("timeseries", (), seed=1, n=4000, noise=0.0)
    return data


def test_timeseries_base_is_the_presliding_law(series):
    p = BASE_TRUTH["timeseries"]
    t, x = series.columns["t"], series.columns["x"]
    expected = presliding_force(t, x, p["Fc"], p["Fs"], p["V"], p["delta"], p["s"])
    np.testing.assert_allclose(Problem(series).predict(p), expected, rtol=0, atol=1e-12)


@pytest.mark.parametrize("effect,neutral", [
    ("viscous", {"sigma": 0.0}),
    ("asymmetry", {"Fc_neg": 10.0, "Fs_neg": 15.0}),
    ("offset", {"F_offset": 0.0}),
    ("drift", {"alpha": 0.0}),
    ("inertia", {"m_e": 0.0}),
    ("ripple", {"A": 0.0, "wavelength": 1e-3, "phase": 0.3}),
    ("lag", {"tau": 0.0}),
    ("backlash", {"play": 0.0}),
])
def test_neutral_effect_gives_the_base_model(series, effect, neutral):
    p = BASE_TRUTH["timeseries"]
    base = Problem(series).predict(p)
    with_effect = Problem(series, (effect,)).predict({**p, **neutral})
    np.testing.assert_allclose(with_effect, base, rtol=0, atol=1e-12)


def test_steady_base_is_e2():
    data, _ = make_dataset("steady", (), seed=0, noise=0.0)
    p = BASE_TRUTH["steady"]
    expected = steady_state_force(data.columns["v"], p["Fc"], p["Fs"], p["V"], p["delta"])
    np.testing.assert_allclose(Problem(data).predict(p), expected, rtol=1e-13)


def test_breakaway_base_is_e13_with_avg():
    data, _ = make_dataset("breakaway", (), seed=0, noise=0.0)
    p = BASE_TRUTH["breakaway"]
    expected = breakaway_force(data.columns["k"], p["Fc"], p["Fs"], p["V"], p["delta"], s=1.0,
                               F_hat="avg", z_ba=0.95)
    np.testing.assert_allclose(Problem(data).predict(p), expected, rtol=1e-13)


def test_breakaway_inertia_term_is_the_e12_acceleration():
    # ẍ = dẋ/dt = dẋ/dz · ż with ż = s·ẋ, by finite differences of (E12)
    p = BASE_TRUTH["breakaway"]
    k, s, z = 3.0, 1.0, 0.95
    F_hat = p["Fc"] + (p["Fs"] - p["Fc"]) / 2
    h = 1e-6
    v = presliding_velocity(np.array([z - h, z, z + h]), k, p["Fc"], p["Fs"], p["V"],
                            p["delta"], s, F_hat="avg")
    accel = (v[2] - v[0]) / (2 * h) * s * v[1]
    data, _ = make_dataset("breakaway", (), seed=0, noise=0.0)
    problem = Problem(data, ("inertia",))
    row = np.argmin(np.abs(data.columns["k"] - k))
    k_row = data.columns["k"][row]
    term = problem.predict({**p, "m_e": 1.0})[row] - Problem(data).predict(p)[row]
    expected = accel * (k_row / k) ** 2  # the term scales with k²
    assert term == pytest.approx(expected, rel=1e-6)
    assert term == pytest.approx(k_row**2 / (s * F_hat**2 * z * abs(math.log(z)) ** 3), rel=1e-12)


def test_play_operator_keeps_the_body_within_half_the_play():
    x = np.concatenate([np.linspace(0, 1, 50), np.linspace(1, 0.7, 20), np.linspace(0.7, 2, 40)])
    xc, engaged = play_operator(x, 0.4)
    assert np.all(np.abs(x - xc) <= 0.2 + 1e-15)
    assert xc[0] == x[0] and not engaged[0]
    np.testing.assert_allclose(np.abs(x - xc)[engaged], 0.2, atol=1e-12)
    # while free the body does not move
    free = ~engaged[1:]
    np.testing.assert_array_equal(xc[1:][free], xc[:-1][free])
    # the 0.3 reversal (from sample 51) stays inside the 0.4 play: no engagement back
    assert not engaged[51:70].any()


def test_lag_filter_is_a_first_order_lag():
    t = np.linspace(0, 1, 1001)
    v = np.ones_like(t)
    v[0] = 0.0
    out = lag_filter(v, t, 0.1)
    np.testing.assert_allclose(out, 1 - np.exp(-t / 0.1), atol=1e-12)
    np.testing.assert_array_equal(lag_filter(v, t, 0.0), v)


@pytest.mark.parametrize("kind,effects", [
    ("timeseries", ("asymmetry", "ripple", "backlash")),
    ("steady", ("asymmetry", "offset")),
    ("breakaway", ("dwell", "viscous")),
])
def test_parameter_vector_round_trip(kind, effects):
    data, truth = make_dataset(kind, effects, seed=0)
    problem = Problem(data, effects)
    back = problem.to_params(problem.to_theta(truth))
    assert back.keys() == truth.keys()
    for name, value in truth.items():
        assert back[name] == pytest.approx(value, rel=1e-12), name
