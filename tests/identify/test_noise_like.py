"""A residual above the noise floor that is still noise (its spread uneven, or the floor
reading low) is said to be so, and not called unexplained structure; a residual with
structure that no single variable's smooth function holds (a fast vibration) still is."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify import diagnose, report
from breakaway.identify.fitting import fit_model
from breakaway.identify.models import problem_for
from breakaway.identify.residuals import lag_one_correlation, residual_structure
from breakaway.identify.warnings.floor_low import CHANCE_STDS, floor_low_warnings
from breakaway.identify.synthetic import NOISE, make_dataset, with_force

N = 10_000


def _clean(seed):
    data, truth = make_dataset("timeseries", (), seed=seed, noise=0.0, n=N)
    return data, truth


def test_lag_one_correlation_tells_noise_from_a_sampled_vibration():
    data, _ = _clean(30)
    problem = problem_for(data)
    rng = np.random.default_rng(30)
    t = data.columns["t"]
    spread = 0.2 + 3.0 * np.abs(np.sin(2 * np.pi * 0.3 * t))
    assert abs(lag_one_correlation(spread * rng.standard_normal(N), problem)) < 0.05
    assert lag_one_correlation(np.sin(2 * np.pi * 50.0 * t), problem) > 0.9


@pytest.mark.parametrize("seed", [31, 32])
def test_noise_growing_with_speed_is_not_unexplained(seed):
    data, truth = _clean(seed)
    x, t = data.columns["x"], data.columns["t"]
    v = np.abs(np.gradient(x, t))
    rng = np.random.default_rng(seed)
    spread = NOISE["timeseries"] * (0.3 + 3.0 * v / v.max())
    result = report(diagnose(with_force(data, data.columns["F"] + spread * rng.standard_normal(N))))
    assert result["effects"] == []
    assert result["unexplained"] is False
    codes = [w["code"] for w in result["warnings"]]
    assert "floor-low" in codes
    message = next(w["message"] for w in result["warnings"] if w["code"] == "floor-low")
    assert "along v" in message and "no effect is missing" in message
    for name in ("Fc", "Fs"):
        assert result["final"]["params"][name] == pytest.approx(truth[name], rel=0.02)


def test_a_fast_vibration_outside_the_library_stays_unexplained():
    # 50 Hz at 1 kHz sampling: no binned function of t holds it, but it is no noise
    data, _ = _clean(33)
    t = data.columns["t"]
    rng = np.random.default_rng(33)
    force = data.columns["F"] + 0.15 * np.sin(2 * np.pi * 50.0 * t) \
        + NOISE["timeseries"] * rng.standard_normal(N)
    result = report(diagnose(with_force(data, force)))
    assert result["unexplained"] is True
    assert "floor-low" not in [w["code"] for w in result["warnings"]]


@pytest.mark.parametrize("seed", [0, 3])
def test_a_short_steady_curve_correlating_by_chance_is_noise_like(seed):
    # 40 set-points of white noise: successive residuals correlate by up to ±0.32 (two
    # standard errors, 2/√39) by chance, so a floor reading low says so; a bend the
    # model lacks, on the same rows, still counts as structure
    data, truth = make_dataset("steady", (), seed=seed, n=40)
    fit = fit_model(data, (), starts=[truth])
    residual = fit.residual()
    assert 0.1 < abs(lag_one_correlation(residual, fit.problem)) < CHANCE_STDS / np.sqrt(39)
    structure = residual_structure(residual, fit.problem, white=False)
    codes = [w["code"] for w in floor_low_warnings(fit, fit.rmse / 1.5, structure)]
    assert codes == ["floor-low"]
    v = data.columns["v"]
    bent = with_force(data, data.columns["F"] + 3 * fit.rmse * np.sin(np.log(np.abs(v))))
    bent_fit = fit_model(bent, (), starts=[truth])
    structure = residual_structure(bent_fit.residual(), bent_fit.problem, white=False)
    assert floor_low_warnings(bent_fit, bent_fit.rmse / 1.5, structure) == []
