"""Selection under misspecification (issues 19 and 26): an effect with a clear signature
of its own is accepted next to a larger unknown; a stand-in for the unknown is not."""

from __future__ import annotations

import functools
from types import SimpleNamespace

import numpy as np
import pytest

from breakaway.identify import diagnose, parse_csv, report
from breakaway.identify.effects import EFFECTS
from breakaway.identify.fitting import fit_model, fit_with_effect, refit
from breakaway.identify.indistinguishable import beyond_nested
from breakaway.identify.judgement import Judge
from breakaway.identify.selection import Selection
from breakaway.identify.synthetic import NOISE, _dataset, make_dataset, with_force
from breakaway.presliding import motion_direction, presliding_force_from_target
from breakaway.steady import stribeck_magnitude

from .machines import servo_axis


def _with_vibration(seed, amplitude=2.5):
    """Strokes whose negative direction slides 10 % softer, under a 7.3 Hz vibration of
    the force outside the library and far larger than the asymmetry."""
    data, _ = make_dataset("timeseries", ("asymmetry",), seed=seed, n=10_000,
                           params={"Fc_neg": 9.0, "Fs_neg": 13.5})
    t = data.columns["t"]
    return with_force(data, data.columns["F"] + amplitude * np.sin(2 * np.pi * 7.3 * t))


def _with_transient(seed, amplitude=5.0):
    """Strokes with a slight asymmetry and a large force transient after each reversal
    (outside the library: a presliding shape of its own)."""
    data, _ = make_dataset("timeseries", ("asymmetry",), seed=seed, n=10_000,
                           params={"Fc_neg": 9.5, "Fs_neg": 14.25})
    problem = fit_model(data).problem
    t = data.columns["t"]
    last, _ = problem._last_reversal()
    return with_force(data, data.columns["F"]
                      + amplitude * problem.d * np.exp(-(t - t[last]) / 0.05))


@pytest.mark.parametrize("seed", [2, 3])
def test_an_effect_next_to_a_larger_unknown_passes_on_its_heldout_gain(seed):
    data = _with_vibration(seed)
    base = fit_model(data)
    trial = fit_with_effect(data, base, "asymmetry")
    share = (base.rmse**2 - trial.rmse**2) / (base.rmse**2 - NOISE["timeseries"] ** 2)
    assert share < 0.25  # a quarter of the residual above the floor: the old rule refused it
    verdict = Judge(data, NOISE["timeseries"]).judge(base, trial)
    assert verdict.reason is None
    assert verdict.heldout < 0.95 * verdict.current_heldout
    result = report(diagnose(data))
    # a level effect is named (offset is nested in asymmetry), and the vibration is
    # left unexplained rather than passed off as a library effect
    assert result["effects"] and set(result["effects"]) <= {"asymmetry", "offset"}
    assert result["unexplained"] is True


def test_a_stand_in_for_an_unknown_is_refused_and_a_true_effect_is_not():
    data = _with_transient(2)
    base = fit_model(data)
    curve = fit_with_effect(data, base, "viscous-power")
    assert curve.bic < base.bic - 10  # it would pass on the BIC alone
    # a flat σ·|v|^n imitates the transient by taking the Coulomb level
    assert curve.params["n"] < 0.5 and curve.params["Fc"] < 0.01 * base.params["Fc"]
    result = report(diagnose(data))
    assert "viscous-power" not in result["effects"]
    assert "takes the Coulomb level" in result["candidates"]["viscous-power"]["reason"]
    # a true effect is accepted
    true_data, truth = make_dataset("timeseries", ("viscous-power",), seed=11, n=10_000)
    true_base = fit_model(true_data)
    true_fit = fit_with_effect(true_data, true_base, "viscous-power")
    assert Judge(true_data, NOISE["timeseries"]).judge(true_base, true_fit).reason is None


def test_inertia_on_a_single_frequency_sine_is_named_and_its_twin_said():
    # a sine of displacement: a = -w^2 x, which a stiffness would give as well. The
    # physical candidate is credited first (the force here is an inertia's), and the
    # report says that a dependence on x would predict the same
    t = np.arange(6000) / 1000.0
    x = 0.004 * np.sin(2 * np.pi * 1.3 * t)
    v = np.gradient(x, t)
    g = stribeck_magnitude(v, 10.0, 15.0, 0.005, 1.5)
    F = presliding_force_from_target(x, motion_direction(x) * g, 2000.0)
    F = F + 30.0 * np.gradient(v, t) + 0.05 * np.random.default_rng(0).standard_normal(t.size)
    result = report(diagnose(_dataset("timeseries", {"t": t, "x": x, "F": F})))
    assert result["effects"] == ["inertia"]
    assert result["final"]["params"]["m_e"] == pytest.approx(30.0, rel=0.05)
    twin = [w for w in result["warnings"]
            if w["code"] == "indistinguishable" and w["parameter"] == "m_e"]
    assert twin and "depends smoothly on x" in twin[0]["message"]
    # on strokes of many lengths and speeds inertia is its own: no such warning
    strokes, _ = make_dataset("timeseries", ("inertia",), seed=11, n=10_000)
    result = report(diagnose(strokes))
    assert result["effects"] == ["inertia"]
    assert not [w for w in result["warnings"] if w["code"] == "indistinguishable"]


def test_a_lag_crowded_after_reversals_stands_in_for_the_presliding_shape():
    # a force transient after each reversal (a presliding shape of the rig's own): a
    # lag fitted to it gains only where the presliding shape decides
    data = _with_transient(2)
    lag = fit_with_effect(data, fit_model(data), "lag")
    reason = EFFECTS["lag"].unresolved(lag.problem, lag.params)
    assert reason and "stands in for that shape" in reason
    # the servo's presliding misfit: with the rows after each reversal weighted by how
    # surely x's counts let them be predicted, the lag beside the final model shrinks to
    # less than the time v is taken over, and is not named (seed 0: its final model is
    # the inertia and the offset that reads its asymmetry: test_machines' gap)
    final = diagnose(parse_csv(servo_axis(0).csv)).final
    assert set(final.effects) == {"inertia", "offset"}
    beside = fit_with_effect(final.problem.data, final, "lag")
    assert "no longer than the time v is taken over" in \
        EFFECTS["lag"].unresolved(beside.problem, beside.params)
    # a true frictional lag is not refused
    true_data, truth = make_dataset("timeseries", ("lag",), seed=11, n=10_000)
    true_fit = fit_model(true_data, ("lag",), starts=[truth])
    assert EFFECTS["lag"].unresolved(true_fit.problem, true_fit.params) is None


def _power_fit(n, se, bic, rmse, rows=400):
    from types import SimpleNamespace

    data = SimpleNamespace(unit=lambda linear: linear, weights=None)
    why = {"n": None if se is not None else "at-bound"}
    return SimpleNamespace(params={"n": n}, stderr={"n": se}, determined={"n": se is not None},
                           bic=bic, rmse=rmse, n=rows, problem=SimpleNamespace(data=data),
                           assessment=SimpleNamespace(why=why))


def test_a_curve_that_barely_bends_is_named_straight():
    from breakaway.identify.indistinguishable import power_is_preferred

    # n = 1.08 ± 0.02 is 4 standard errors from 1 (how an encoder's counts bend v can
    # make that on a straight viscous term), but the curve lowers the RMSE by 0.15 %
    power = _power_fit(1.08, 0.02, bic=-9000.0, rmse=0.06490)
    viscous = _power_fit(1.0, None, bic=-8980.0, rmse=0.06500)
    preferred, why = power_is_preferred(power, viscous, 0.0650, 0.0651)
    assert not preferred and "lowers the RMSE by only 0.15 %" in why
    # the same exponent with a visible gain is a curve
    preferred, why = power_is_preferred(power, _power_fit(1.0, None, -8980.0, 0.0680),
                                        0.0650, 0.0681)
    assert preferred, why


def test_a_heldout_error_below_the_fits_own_does_not_speak_for_that_fit():
    from breakaway.identify.indistinguishable import power_is_preferred

    power = _power_fit(2.0, 0.01, bic=-480.0, rmse=0.0053)
    # refits of viscous on the held-out chunks found 0.0058, but the viscous fit the
    # report would name has 0.0087 on the record itself
    viscous = _power_fit(1.0, None, bic=-436.0, rmse=0.0087)
    preferred, why = power_is_preferred(power, viscous, 0.0060, 0.0058)
    assert preferred, why
    # a viscous fit whose held-out error is above the curve's still wins
    preferred, why = power_is_preferred(power, _power_fit(1.0, None, -436.0, 0.0055),
                                        0.0060, 0.0059)
    assert not preferred and "held-out error prefers viscous" in why


def test_an_exponent_on_its_bound_is_judged_by_the_likelihood_ratio():
    from breakaway.identify.indistinguishable import power_is_preferred

    # n on the bound 0.2 has no standard error; 400 rows whose RMSE falls by 20 % put
    # n = 1 13 standard errors away by the likelihood ratio
    power = _power_fit(0.2, None, bic=-500.0, rmse=0.008)
    viscous = _power_fit(1.0, None, bic=-420.0, rmse=0.010)
    preferred, why = power_is_preferred(power, viscous, 0.0081, 0.0102)
    assert preferred and "likelihood ratio" in why
    # a curve on its bound that the straight line fits within 3 standard errors is viscous
    close = _power_fit(1.0, None, bic=-499.0, rmse=0.00801)
    preferred, why = power_is_preferred(power, close, 0.0081, 0.0082)
    assert not preferred and "within 3 standard errors" in why


def test_a_quadratic_joint_curve_is_not_a_viscous_fit_with_fc_on_its_bound():
    # seed 3 of the n = 2 joint: viscous imitates the curve with Fc bent to 0 and a
    # Stribeck drop, and its held-out refits found a better optimum than its own fit
    from .machines import joint_steady

    recording = joint_steady(3, exponent=2.0)
    r = report(diagnose(parse_csv(recording.csv)))
    assert r["effects"] == ["viscous-power"]
    final = r["final"]
    assert final["determined"]["Fc"] and final["determined"]["n"]
    assert final["params"]["Fc"] == pytest.approx(recording.truth["Fc"], rel=0.1)
    assert final["params"]["n"] == pytest.approx(2.0, abs=0.1)
    # the peak is beyond the data, and the bound a steady curve sets on it is its value
    # at the slowest speed (here Fc), not its largest force (at the fastest speed)
    peak = next(w["message"] for w in r["warnings"]
                if w["code"] == "beyond-data" and w["parameter"] == "Fs")
    bound = float(peak.split("≥ ")[1].split()[0])
    assert bound == pytest.approx(final["params"]["Fc"], rel=0.05)


def test_a_half_that_holds_sigma_only_loosely_does_not_refuse_it():
    # seed 6 of the viscous strokes: the second half's slow strokes trade σ against the
    # Stribeck curve (21 ± 41 against the first half's 119 ± 5 N·s/m) and fit as well
    # with the record's σ; the whole record names viscous at its truth
    from .machines import families

    recording = families()["strokes-viscous"](6)
    r = report(diagnose(parse_csv(recording.csv)))
    assert r["effects"] == ["viscous"]
    assert r["final"]["params"]["sigma"] == pytest.approx(recording.truth["sigma"], rel=0.1)


@pytest.mark.parametrize("truth,first", [({}, "offset"),
                                         ({"Fc_neg": 8.0, "Fs_neg": 14.0}, "asymmetry")])
def test_an_asymmetry_must_earn_its_second_level_against_an_offset(truth, first):
    # an offset moves both directions' levels alike: an asymmetry fits it as well with a
    # second Stribeck level, and offered first (a lower BIC over every row, on a real
    # record) it must pass the verdict against the offset; a direction difference of its
    # own does
    effects = ("offset",) if not truth else ("asymmetry",)
    data, _ = make_dataset("timeseries", effects, seed=3, n=6000, params=truth or None)
    base = fit_model(data)
    trials = {e: refit(data, fit_with_effect(data, base, e)) for e in ("asymmetry", "offset")}
    search = Selection(data, NOISE["timeseries"], lambda fraction, message: None)
    assert search._parsimonious(["asymmetry", "offset"], trials)[0] == first



def test_a_curve_trapped_worse_than_the_straight_line_is_fitted_again_from_it():
    # a curve σ·|v|ⁿ holds the straight line as n = 1: a viscous-power fit left worse than
    # the viscous one (its own starts in another basin) starts again where viscous ended
    speeds = np.geomspace(0.02, 3.0, 20)
    v = np.concatenate([speeds, -speeds])
    rng = np.random.default_rng(1)
    F = np.sign(v) * (stribeck_magnitude(v, 3.0, 3.6, 0.3, 1.0) + 0.37 * np.abs(v) ** 1.86)
    data = _dataset("steady", {"v": v, "F": F + 0.02 * rng.standard_normal(v.size)})
    base = fit_model(data)
    viscous = fit_model(data, ("viscous",), starts=[{"Fc": 3.0, "Fs": 3.6, "V": 0.3,
                                                     "delta": 1.0, "sigma": 1.0}])
    trapped = fit_model(data, ("viscous-power",), starts=[{**viscous.params, "Fc": 0.5,
                                                          "sigma": 1e-3, "n": 2.9}],
                        screen=1, max_nfev=1)
    assert trapped.rmse > viscous.rmse
    search = Selection(data, 0.02, lambda fraction, message: None)
    trials = {"viscous": viscous, "viscous-power": trapped}
    search._extend_nested(base, trials)
    assert trials["viscous-power"].rmse < viscous.rmse
    assert trials["viscous-power"].params["n"] == pytest.approx(1.86, abs=0.15)
    assert trials["viscous"] is viscous


def test_a_pair_is_named_only_where_each_earns_its_place_beside_the_other():
    # a heavy carriage's one-direction run: inertia refused alone as unstable (a half
    # of constant acceleration gives m_e whatever the levels leave), then offered with a
    # drift that lowers the RMSE by 0.05 % beside it
    from .rigzoo import families

    recording = families()["constant-acceleration-hum"](2000)
    r = report(diagnose(parse_csv(recording.csv)))
    assert "drift" not in r["effects"]
    assert "inertia" in r["effects"]
    assert r["final"]["params"]["m_e"] == pytest.approx(recording.truth["m_e"], rel=0.1)


@functools.cache
def _torque_estimate_report():
    """A joint's torque estimate (rig zoo, seed 2004) and its report: two tests read
    it, and its fit takes half a minute."""
    from .rigzoo import families

    recording = families()["estimated-torque"](2004)
    return recording, report(diagnose(parse_csv(recording.csv)))


def test_a_curve_chosen_before_the_effects_beside_it_must_still_earn_its_exponent():
    # a joint's torque estimate (programme less a gravity model): the curve came in
    # before the inertia and the offset with n = 0.64 ± 0.09 for a straight viscous
    # term, and took 18 % of Fc; beside them the exponent no longer earns its place.
    # With the rows where the joint stops under its programme weighed apart, the
    # curve no longer comes in at all: its exponent's size is not determined
    _, r = _torque_estimate_report()
    assert "viscous" in r["effects"] and "viscous-power" not in r["effects"]
    assert not r["candidates"]["viscous-power"]["accepted"]


def test_the_bias_of_a_torque_estimate_stays_named_beside_a_straightened_curve():
    recording, r = _torque_estimate_report()
    assert "offset" in r["effects"]
    assert r["final"]["params"]["Fc"] == pytest.approx(recording.truth["Fc"], rel=0.1)


def test_a_convex_curve_is_not_straightened_into_a_line_through_the_origin():
    # a gearbox's steady curve rising as |v|^1.86: the straight line meets it only with
    # Fc on its bound 0, which describes no curve with a level at rest
    from .rigzoo import families

    recording = families()["gearbox-steady"](2004)
    r = report(diagnose(parse_csv(recording.csv)))
    assert r["effects"] == ["viscous-power"]
    assert r["final"]["params"]["n"] == pytest.approx(recording.truth["n"], abs=0.15)


def test_an_asymmetry_whose_levels_do_not_stand_apart_is_not_named():
    # a coarse encoder with spikes: the negative Coulomb level came out at the positive
    # one's value (0.1796 ± 0.0007 against 0.1798), the Stribeck level beyond the data,
    # and the asymmetry was named on the misfit of a presliding shape 50 times too soft
    from .rigzoo import families

    recording = families()["coarse-encoder-spikes"](2000)
    r = report(diagnose(parse_csv(recording.csv)))
    assert "asymmetry" not in r["effects"]
    assert "within 2 standard errors of 0" in r["candidates"]["asymmetry"]["reason"]
    assert r["final"]["params"]["Fc"] == pytest.approx(recording.truth["Fc"], rel=0.02)


def _judging_out(data, names):
    """A search of ``data`` whose judgement refuses the effects ``names`` beside any
    model (and judges the rest as the search does)."""
    search = Selection(data, NOISE["timeseries"], lambda fraction, message: None)
    judge = search.judgement.judge

    def judged(reduced, fit):
        if (set(fit.effects) - set(reduced.effects)) & names:
            return SimpleNamespace(reason="the BIC falls by 3, less than the 10 required")
        return judge(reduced, fit)

    search.judgement.judge = judged
    return search


def test_an_effect_that_no_longer_earns_its_place_beside_the_rest_is_dropped():
    # an effect accepted in an early round (an asymmetry, against a model whose straight
    # viscous term misfit each direction differently) that beside the model the search
    # ends with no longer passes the verdict goes, with its reason, though the BIC alone
    # would keep it
    data, truth = make_dataset("timeseries", ("viscous", "asymmetry"), seed=2, n=6000)
    fit = fit_model(data, ("viscous", "asymmetry"), starts=[truth])
    search = _judging_out(data, {"asymmetry"})
    final, _ = search.backward(fit, search.heldout(fit))
    assert final.effects == ("viscous",)
    assert search.verdicts["asymmetry"].reason.startswith(
        "no longer earns its place beside viscous: the BIC falls by 3")


def test_a_gearbox_timed_over_its_plateaus_lets_no_asymmetry_in():
    # a gearbox driven through speed plateaus on an encoder of a few counts a sample:
    # over the narrowest windows of eight counts its plateaus' speeds scattered by a
    # count in a few, the straight viscous term misfit each direction differently, and
    # an asymmetry came in, to be dropped by the backward pass; timed over the plateaus,
    # the asymmetry never earns its place
    from .rigzoo import families

    recording = families()["gearbox-timeseries"](2003)
    r = report(diagnose(parse_csv(recording.csv)))
    assert r["effects"] == ["viscous-power"]
    assert r["candidates"]["asymmetry"]["reason"].startswith("the BIC falls by")
    assert r["final"]["params"]["Fc"] == pytest.approx(recording.truth["Fc"], rel=0.02)


def test_a_weighted_fits_gain_is_not_refused_for_the_plain_rmse():
    # a joint moved by hand on a 0.18° encoder: the viscous term lowers the error of the
    # rows the fit weighs (0.079 → 0.044 N·m) and raises the plain RMSE by 1 %, which is
    # the tenth of the rows at turns whose prediction the encoder's counts leave open
    from .rigzoo import families

    recording = families()["hand-moved"](2000)
    r = report(diagnose(parse_csv(recording.csv)))
    assert r["effects"] == ["offset", "viscous"]
    params, truth = r["final"]["params"], recording.truth
    assert params["Fc"] == pytest.approx(truth["Fc"], rel=0.05)
    assert params["sigma"] == pytest.approx(truth["sigma"], rel=0.2)


def test_an_rmse_that_rises_beside_an_allowance_is_said_to_rise():
    from types import SimpleNamespace

    # the candidate's residual is mostly a smooth dependence (which the allowance takes
    # off both sides alike): judged beside it the BIC falls, yet the RMSE the fit
    # minimises rises, and the verdict says so, not that it "falls by only -x %"
    rng = np.random.default_rng(4)
    n = 400
    u = np.linspace(0.0, 1.0, n)
    H = np.column_stack([np.sin(np.pi * k * u) for k in (1, 2, 3)])
    before = 0.1 * rng.standard_normal(n)
    after = H @ np.array([0.3, -0.2, 0.1]) + 0.001 * rng.standard_normal(n)

    def fit(residual, names):
        problem = SimpleNamespace(kind="steady", names=names, stop_rows=lambda params: None)
        return SimpleNamespace(n=n, residual=lambda: residual, problem=problem, rmse=0.1,
                               params={})

    data = SimpleNamespace(weights=None, unit=lambda linear: linear)
    judge = Judge(data, 0.1)
    reason = judge._evidence(fit(before, ("Fc",)), fit(after, ("Fc", "sigma")), H, 10.0)
    rise = 100 * (np.sqrt(np.mean(after**2)) / np.sqrt(np.mean(before**2)) - 1)
    assert reason == (f"the RMSE rises by {rise:.2g} %, from "
                      f"{np.sqrt(np.mean(before**2)):.4g} to {np.sqrt(np.mean(after**2)):.4g} N")


def test_once_an_inertia_is_named_the_rows_where_a_jumps_weigh_for_what_a_holds_there():
    # a heavy carriage (31 kg, 3 m/s², braked at the same rate): m_e times the error of
    # a where it jumps was 97 % of the weighted squared residual, on 30 of 1127 rows,
    # and the viscous rise (σ = 1.46) was refused for an RMSE "falling by only 1.5 %"
    from . import rigzoo

    recording = rigzoo.constant_acceleration(2003)
    found = diagnose(parse_csv(recording.csv))
    assert found.effects == ["inertia", "viscous"]
    params = found.final.params
    assert params["sigma"] == pytest.approx(recording.truth["sigma"], rel=0.1)
    assert params["m_e"] == pytest.approx(recording.truth["m_e"], rel=0.02)
    weights = found.final.problem.data.weights
    t, a_true = recording.hidden["t"], recording.hidden["acceleration"]
    jumps = t[1:][np.diff(a_true) != 0]
    assert jumps.size == 2  # the start and the braking (the record ends at the stop)
    # beside each jump the weights fall by orders of magnitude; elsewhere they are kept
    for jump in jumps:
        assert np.min(weights[np.abs(t - jump) < 0.003]) < 0.01
    far = np.all(np.abs(t[:, None] - jumps[None, :]) > 0.1, axis=1)
    assert np.median(weights[far]) == pytest.approx(1.0)


def test_a_size_that_trades_only_with_a_drop_the_data_do_not_resolve_is_read_without_it():
    # a carriage under mains hum (seed 5 of the rig zoo's family): beside the inertia the
    # viscous trial placed a drop of δ = 0.14 at V far beyond the fastest speed, which
    # bent like the rise and left σ "a standard error larger than its value"; without
    # that drop σ is determined, and the rise is named at its size
    from . import rigzoo

    recording = rigzoo.constant_acceleration(5, hum=True)
    found = diagnose(parse_csv(recording.csv))
    assert found.effects == ["inertia", "viscous"]
    assert found.final.determined["sigma"]
    assert found.final.params["sigma"] == pytest.approx(recording.truth["sigma"], rel=0.25)


def test_an_asymmetry_whose_drops_the_data_do_not_show_says_nothing_beyond_an_offset():
    # an offset is an asymmetry whose levels differ by one shift: what the asymmetry adds
    # is that the two directions' Stribeck drops differ, and a drop the data do not
    # determine, or whose level lies below a force they hold without sliding, is no drop
    def asymmetry(Fs, Fs_neg, determined=True, bound=None, apart=False):
        return SimpleNamespace(
            params={"Fc": 0.83, "Fs": Fs, "Fc_neg": 1.02, "Fs_neg": Fs_neg},
            determined={"Fc": True, "Fs": determined, "Fc_neg": True, "Fs_neg": True},
            assessment=SimpleNamespace(bound=bound or {}),
            problem=SimpleNamespace(breakaways_apart=lambda params: apart))

    assert beyond_nested("asymmetry", "offset", asymmetry(0.90, 1.33)) is None
    # drops seen only where each direction breaks away, at its own end of the travel
    assert "at one place of its own" in beyond_nested("asymmetry", "offset",
                                                 asymmetry(0.90, 1.33, apart=True))
    # no drop one way and a drop the other: the drops differ, which no offset gives
    assert beyond_nested("asymmetry", "offset",
                         asymmetry(0.83, 1.33, False, {"Fs": "lower"})) is None
    assert beyond_nested("asymmetry", "offset", asymmetry(0.83, 1.02)) \
        == "it has no Stribeck drop either way, so it says nothing that offset does not"
    assert beyond_nested("asymmetry", "offset", asymmetry(0.90, 1.33), beyond={"Fs"}) \
        .startswith("its Fs = 0.9 is not what the data determine")
    # a missing drop that a held force contradicts is no result either
    assert beyond_nested("asymmetry", "offset", asymmetry(0.83, 1.33, False, {"Fs": "lower"}),
                         beyond={"Fs"}).startswith("its Fs = 0.83 ")
    assert "Fs = 0.9 " in beyond_nested("asymmetry", "offset", asymmetry(0.90, 1.33, False))
    # only nested pairs are compared so
    fit = asymmetry(0.90, 1.33)
    assert beyond_nested("viscous-power", "viscous", fit) is None
    assert beyond_nested("offset", "asymmetry", fit) is None
    del fit.params["Fs"]
    assert beyond_nested("asymmetry", "offset", fit).startswith("it has no Fs")


def test_a_curve_that_no_longer_earns_its_place_leaves_its_straight_form_to_be_judged():
    # the search took the curve σ·|v|ⁿ over the straight line in an early round (the
    # line's verdict: "viscous-power describes the data better"); beside the effects
    # that came after, the curve no longer earns its place. Dropping it would leave the
    # rise the line had shown unnamed: the line is judged in its place, as an effect in
    # a forward round is
    data, truth = make_dataset("timeseries", ("offset", "viscous"), seed=2, n=6000)
    curve = fit_model(data, ("offset", "viscous-power"), starts=[{**truth, "n": 1.0}])
    search = _judging_out(data, {"viscous-power"})
    final, _ = search.backward(curve, search.heldout(curve))
    assert set(final.effects) == {"offset", "viscous"}
    assert final.params["sigma"] == pytest.approx(truth["sigma"], rel=0.05)
    assert search.verdicts["viscous-power"].reason.startswith(
        "named viscous, its special case: no longer earns its place beside offset")
    # where the line does not earn its place either, the curve goes without it
    search = _judging_out(data, {"viscous-power", "viscous"})
    final, _ = search.backward(curve, search.heldout(curve))
    assert final.effects == ("offset",)
