"""Least-squares fits: round trips on seeded synthetic data, bounds, uncertainties and
failure modes (in the manner of scipy's test_minpack)."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify import FitError, fit_model
from breakaway.identify.fitting import fit_with_effect
from breakaway.identify.models import problem_for as Problem
from breakaway.identify.synthetic import make_dataset


@pytest.mark.parametrize("kind", ["timeseries", "steady", "breakaway"])
def test_noiseless_round_trip(kind):
    data, truth = make_dataset(kind, (), seed=2, noise=0.0,
                               n=6000 if kind == "timeseries" else None)
    fit = fit_model(data)
    for name, value in truth.items():
        assert fit.params[name] == pytest.approx(value, rel=1e-4), name
    assert fit.rmse < 1e-6 * truth["Fc"]


@pytest.mark.parametrize("kind", ["timeseries", "steady", "breakaway"])
def test_noisy_estimates_lie_within_their_uncertainties(kind):
    data, truth = make_dataset(kind, (), seed=3, n=6000 if kind == "timeseries" else None)
    fit = fit_model(data)
    for name in ("Fc", "Fs", "delta"):
        err = abs(fit.params[name] - truth[name])
        assert 0 < fit.stderr[name] < 0.05 * truth[name]
        assert err < 4.5 * fit.stderr[name], name


def test_fit_returns_what_the_model_function_takes():
    data, truth = make_dataset("steady", ("offset",), seed=1)
    base = fit_model(data)
    fit = fit_with_effect(data, base, "offset")
    np.testing.assert_array_equal(Problem(data, ("offset",)).predict(fit.params), fit.prediction)
    assert fit.params["F_offset"] == pytest.approx(truth["F_offset"], rel=0.05)


def test_stribeck_level_never_below_coulomb():
    # data without any Stribeck hump: the fit sits on the bound Fs = Fc
    data, _ = make_dataset("steady", (), seed=4, params={"Fs": 10.0})
    fit = fit_model(data)
    assert fit.params["Fs"] >= fit.params["Fc"]
    assert fit.params["Fs"] - fit.params["Fc"] < 0.05
    assert 0.05 <= fit.params["delta"] <= 10.0


def test_rows_of_small_weight_do_not_pull_the_fit():
    # rows whose error is large (x's reading, say) are given a small weight: the fit
    # is the one the other rows make, and the plain RMSE still covers every row
    from dataclasses import replace
    data, truth = make_dataset("steady", (), seed=6, noise=0.0)
    F = data.columns["F"].copy()
    spoiled = np.arange(data.n) % 5 == 0
    F[spoiled] += 0.3 * truth["Fc"] * np.sign(data.columns["v"][spoiled])
    bent = replace(data, columns={**data.columns, "F": F})
    plain = fit_model(bent)
    weighted = fit_model(replace(bent, weights=np.where(spoiled, 1e-8, 1.0)))
    assert abs(plain.params["Fc"] / truth["Fc"] - 1) > 0.02
    for name, value in truth.items():
        assert weighted.params[name] == pytest.approx(value, rel=1e-3), name
    assert weighted.rmse == pytest.approx(
        np.sqrt(np.mean((F - weighted.prediction) ** 2)), rel=1e-9)
    assert weighted.bic < plain.bic  # the weighted sum of squares


def test_rows_subset_predicts_every_row():
    data, _ = make_dataset("timeseries", (), seed=5, n=3000)
    fit = fit_model(data, rows=np.arange(2400))
    assert fit.n == 2400
    assert fit.prediction.shape == (3000,)


def test_too_few_rows_for_the_parameters():
    data, _ = make_dataset("steady", (), seed=0)
    with pytest.raises(FitError, match="3 rows cannot determine 4 parameters"):
        fit_model(data, rows=np.arange(3))


def test_effects_need_starting_values():
    data, _ = make_dataset("steady", (), seed=0)
    with pytest.raises(ValueError, match="starts are needed"):
        fit_model(data, ("offset",))


def test_unknown_effect_is_refused():
    data, _ = make_dataset("steady", (), seed=0)
    with pytest.raises(KeyError, match="spin"):
        Problem(data, ("spin",))
