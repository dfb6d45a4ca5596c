"""A correlation above 0.99 is a long valley of the fit, not a free parameter: a
parameter is determined when the fit, held at the ends of its interval (± 2 standard
errors) with the others refitted, is worse there as its standard error promises."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify import identify, parse_csv
from breakaway.identify.fitting import fit_model, fit_with_effect
from breakaway.identify.profile import confirm_correlated, follows_no_variable

FC, EXPONENT = 2.0, 0.5


def _gearbox_csv(seed: int, v_min: float, v_max: float, points: int = 20) -> bytes:
    """A gearbox's steady curve F = sign(v)·(Fc + σ·|v|ⁿ), rising by Fc at v_max, the
    set-points geometric, 1 % scatter."""
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(v_min, v_max, points)
    v = np.concatenate([speeds, -speeds])
    sigma = FC / v_max**EXPONENT
    F = np.sign(v) * (FC + sigma * np.abs(v) ** EXPONENT) + 0.01 * FC * rng.standard_normal(v.size)
    return "\n".join(["v [rad/s],F [N·m]"] + [f"{a:.6g},{b:.6f}" for a, b in zip(v, F)]).encode()


def _gearbox_curve(seed: int, v_min: float, v_max: float):
    """The fit of base + viscous-power to :func:`_gearbox_csv`'s curve."""
    data = parse_csv(_gearbox_csv(seed, v_min, v_max))
    return fit_with_effect(data, fit_model(data), "viscous-power")


@pytest.mark.parametrize("seed", [1, 2])
def test_a_tight_valley_is_determined_although_its_parameters_move_together(seed):
    # from 0.5 rad/s up, a concave rise trades with Fc (r < −0.99), but 20 set-points a
    # direction over a decade of speed fix both to a few per cent
    fit = _gearbox_curve(seed, 0.5, 4.0)
    a = fit.assessment
    assert a.why["Fc"] == "correlated:sigma" and a.correlated["Fc"]["r"] < -0.99
    confirm_correlated(fit)
    assert a.determined["Fc"] and a.why["Fc"] is None and "Fc" not in a.correlated
    assert a.determined["sigma"] and a.determined["n"]
    # the standard error it is reported with is the one the truth lies within
    assert abs(fit.params["Fc"] - FC) < 3 * a.stderr["Fc"]
    assert a.stderr["Fc"] < 0.1 * FC
    assert abs(fit.params["n"] - EXPONENT) < 3 * a.stderr["n"]


def test_a_valley_that_flattens_stays_a_combination():
    # a factor of two in speed: at Fc − 2·SE the profile rises by less than half of
    # what the standard error promises, so Fc and σ stay tied, the combination reported
    fit = _gearbox_curve(1, 2.0, 4.0)
    a = fit.assessment
    assert a.why["Fc"] == "correlated:sigma"
    confirm_correlated(fit)
    assert a.why["Fc"] == "correlated:sigma" and not a.determined["Fc"]
    assert a.correlated["Fc"]["with"] == "sigma"
    assert a.correlated["Fc"]["stderr"] < 0.2 * a.stderr["Fc"]


def test_nothing_is_confirmed_beside_a_parameter_on_its_bound():
    # held at its bound, n cannot follow the valley past it: the profile would rise
    # where the data do not
    fit = _gearbox_curve(1, 0.5, 4.0)
    fit.assessment.bound["n"] = "lower"
    confirm_correlated(fit)
    assert fit.assessment.why["Fc"] == "correlated:sigma"
    assert not fit.assessment.determined["Fc"]


@pytest.mark.parametrize("seed", [1, 3])
def test_the_report_of_a_white_residual_says_what_the_profile_found(seed):
    # from 0.1 rad/s: Fc correlated with σ (r < −0.99) in the fit, the drop unresolved
    # (Fc the level of the model without it), the residual white
    report = identify(parse_csv(_gearbox_csv(seed, 0.1, 4.0)))
    assert report["effects"] == ["viscous-power"] and report["residual_white"]
    final = report["final"]
    assert final["determined"]["Fc"] and final["determined"]["n"]
    assert abs(final["params"]["Fc"] - FC) < 3 * final["stderr"]["Fc"] < 0.1 * FC
    assert not [w for w in report["warnings"]
                if w["code"] == "undetermined" and w["parameter"] in ("Fc", "sigma", "n")]


def test_an_exponent_that_moves_with_fc_is_judged_by_the_likelihood_ratio():
    # from 0.5 rad/s, n moves with Fc: its standard error is no test of n = 1, the
    # nested fits' likelihood ratio is (the line leaves 3 noise floors, the curve one)
    report = identify(parse_csv(_gearbox_csv(2, 0.5, 4.0)))
    assert report["effects"] == ["viscous-power"]
    assert abs(report["final"]["params"]["n"] - EXPONENT) < 0.05
    reason = report["candidates"]["viscous"]["reason"]
    assert "moving with Fc; its distance from 1 by the likelihood ratio" in reason


def _structure(*strengths):
    """A ``residual_structure`` with these shares, against variables in turn."""
    names = ("x", "t", "v", "time since reversal", "x - x_r", "direction")
    return [{"against": name, "strength": share} for name, share in zip(names, strengths)]


def test_a_misfit_that_follows_no_variable_is_a_disturbance():
    # mains hum 3.5 times the noise floor: a misfit ratio of 3.46, so 92 % of the
    # residual's variance is excess; no variable explains 1.5 % of it
    assert follows_no_variable(_structure(0.015, 0.0057, 0.004, 0.0038, 0.0019), 3.46)


@pytest.mark.parametrize("structure, misfit", [
    # a seal's position dependence: x explains 57 % of a residual 1.74 times its errors
    (_structure(0.571, 0.568, 0.303), 1.74),
    # 4 % along v is a good share of the 17 % excess of a misfit of 1.1
    (_structure(0.04, 0.01), 1.1),
    # no excess, no disturbance
    (_structure(0.0, 0.0), 0.9),
    # a white residual has no structure to judge
    ([], 3.0),
])
def test_a_misfit_that_follows_a_variable_or_none_at_all_is_not_a_disturbance(structure,
                                                                             misfit):
    assert not follows_no_variable(structure, misfit)


def test_under_mains_hum_a_correlated_pair_is_checked_along_its_profile():
    # strokes with 60 Hz hum on the load cell: the rows' misfit is 3 times their
    # expected errors, all of it hum (no variable explains 5 % of the excess, the
    # residual in units of each row's error); Fc and σ, correlated above 0.99, were
    # "undetermined" for that alone, and their profiles hold
    from .rigzoo import families

    recording = families()["strokes-hum"](2032)
    report = identify(parse_csv(recording.csv))
    assert report["unexplained"]  # the hum is still what the model lacks
    final = report["final"]
    for name in ("Fc", "sigma"):
        assert final["determined"][name]
        assert abs(final["params"][name] - recording.truth[name]) < 2 * final["stderr"][name]
    assert final["stderr"]["Fc"] < 0.05 * recording.truth["Fc"]
    assert final["stderr"]["sigma"] < 0.2 * recording.truth["sigma"]


def test_a_profile_whose_valley_runs_a_log_scaled_parameter_through_zero_starts_it_in_range():
    # held at Fc ± 2·SE, the valley's straight line (each parameter's regression on the
    # one held) can take a positive parameter below zero: it starts where the fit left
    # it, not at a value that predicts nothing (a profile that cannot start would rise
    # by nothing, and the parameter is never confirmed)
    from breakaway.identify.profile import _profile_rise

    fit = _gearbox_curve(1, 0.5, 4.0)
    held = fit.params["Fc"] * 1.05
    far = {"V": -2.0 * fit.params["V"] / (held - fit.params["Fc"])}
    assert fit.problem.is_log("V")
    with np.errstate(invalid="raise", divide="raise"):
        rise = _profile_rise(fit, "Fc", held, far, fit.weighted_rss)
    assert rise > 0.0
