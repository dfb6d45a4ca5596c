"""The allowance for a dependence the library lacks."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify.allowance import (
    basis,
    indistinguishable_from,
    residual_without,
    structured_variables,
)
from breakaway.identify.fitting import fit_model, fit_with_effect
from breakaway.identify.synthetic import make_dataset, with_force


def _seal(seed, amplitude=3.0):
    """Strokes whose friction grows smoothly (not periodically) along the travel."""
    data, _ = make_dataset("timeseries", seed=seed, n=8000)
    x = data.columns["x"]
    bump = amplitude * np.tanh((x - x.mean()) / (0.3 * np.ptp(x)))
    d = np.sign(np.gradient(x))
    return with_force(data, data.columns["F"] + d * bump), bump


def test_a_position_dependence_is_found_in_the_residual_and_nowhere_else():
    data, _ = _seal(1)
    fit = fit_model(data)
    found = structured_variables(fit.problem, fit.residual())
    assert "±x" in found
    clean, _ = make_dataset("timeseries", seed=1, n=8000)
    plain = fit_model(clean)
    assert structured_variables(plain.problem, plain.residual()) == ()


def test_the_allowance_takes_the_dependence_but_no_level():
    data, bump = _seal(2)
    fit = fit_model(data)
    H = basis(fit.problem, ("±x",))
    d = fit.problem.d.astype(float)
    # no constant and no direction level: those are the model's (offset, Fc)
    assert np.abs(H.T @ np.ones(data.n)).max() < 1e-8 * data.n
    assert np.abs(H.T @ d).max() < 1e-8 * data.n
    left = residual_without(d * bump, H)
    assert np.std(left) < 0.15 * np.std(d * bump)


def test_a_candidate_the_allowance_could_make_is_not_its_own():
    # on a single-frequency sine, a = -w^2 x: inertia's column lies in a smooth function
    # of x; on strokes of many lengths and speeds it does not
    t = np.arange(6000) / 1000.0
    x = 0.004 * np.sin(2 * np.pi * 1.3 * t)
    from breakaway.identify.synthetic import _dataset
    from breakaway.presliding import motion_direction, presliding_force_from_target
    from breakaway.steady import stribeck_magnitude

    v = np.gradient(x, t)
    F = presliding_force_from_target(x, motion_direction(x) *
                                     stribeck_magnitude(v, 10.0, 15.0, 0.005, 1.5), 2000.0)
    F = F + 30.0 * np.gradient(v, t) + 0.05 * np.random.default_rng(0).standard_normal(t.size)
    sine = _dataset("timeseries", {"t": t, "x": x, "F": F})
    trial = fit_with_effect(sine, fit_model(sine), "inertia")
    assert indistinguishable_from(trial, ("m_e",), basis(trial.problem, ("x",))) == "m_e"
    strokes, _ = make_dataset("timeseries", ("inertia",), seed=11, n=8000)
    trial = fit_with_effect(strokes, fit_model(strokes), "inertia")
    assert indistinguishable_from(trial, ("m_e",), basis(trial.problem, ("x", "±x"))) is None


@pytest.mark.parametrize("kind", ["steady", "breakaway"])
def test_separate_measurements_have_no_unused_variable(kind):
    data, _ = make_dataset(kind, seed=0)
    fit = fit_model(data)
    assert structured_variables(fit.problem, fit.residual()) == ()
