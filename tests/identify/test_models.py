"""Forward models with effects: each effect at its neutral value gives back the base
model, and the base model of each kind is the model core's function."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from breakaway.identify import parse_csv
from breakaway.identify.effects import lag_filter, play_operator
from breakaway.identify.fitting import fit_model
from breakaway.identify.input_error import input_weights
from breakaway.identify.models import problem_for as Problem
from breakaway.identify.models import with_forces
from breakaway.identify.synthetic import BASE_TRUTH, make_dataset
from breakaway.presliding import presliding_force
from breakaway.quasistatic import breakaway_force, presliding_velocity
from breakaway.steady import steady_state_force

from . import cases, machines, rigzoo


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


@pytest.mark.parametrize("count, blocks", [(1e-6, None), (3e-6, [1000, 1500])])
def test_the_body_behind_a_play_is_timed_as_any_position_record(count, blocks):
    # v of the body is taken again only where a window reads a change of the play's
    # edge; everywhere else it is the model positions' v, which an offset leaves alone
    data, _ = make_dataset("timeseries", ("backlash",), seed=1, n=3000)
    read = count * np.round(data.columns["x"] / count)
    data = replace(data, columns={**data.columns, "x": read},
                   segments=blocks or data.segments)
    problem = Problem(data, ("backlash",))
    assert not problem.derivatives.edges and problem.resolution_x == pytest.approx(count)
    for play in (1e-5, 1e-4, 1e-3):
        body, engaged = play_operator(problem.x, play)
        whole = problem.kinematic_velocity(body)
        np.testing.assert_allclose(problem.body_velocity(body, engaged), whole, rtol=1e-12,
                                   atol=1e-12 * float(np.max(np.abs(whole))))


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


# ---------------------------------------------------------------------------------
# stops: where the body may have halted and turned within what the encoder shows
# ---------------------------------------------------------------------------------


def _at_truth(record):
    """``record``'s model with its required effects, evaluated at its hidden truth."""
    names = ("Fc", "Fs", "V", "delta", "s", "sigma", "n", "F_offset", "m_e")
    start = {k: float(record.truth[k]) for k in names if k in record.truth}
    return fit_model(parse_csv(record.csv), tuple(sorted(record.expect.required)),
                     starts=[start], screen=1, max_nfev=1)


def test_a_servo_held_by_a_swinging_command_is_weighed_apart_where_it_stops():
    # a torque command swings through ±Fs while the axis sits on one or two counts: the
    # model at the truth misses the friction there by up to 2 Fs, since the turns it
    # makes within the counts are not read. The stops hold those rows, and weighing
    # by their errors leaves the rows where the reading says what the body did
    record = rigzoo.families()["servo-command"](2)
    fit = _at_truth(record)
    problem, params = fit.problem, fit.params
    missed = np.abs(record.hidden["friction"] - problem.predict(params, sensor=False))
    far = missed > 0.1 * record.truth["Fc"]
    stops = problem.stop_rows(params)
    assert stops is not None
    assert np.mean(stops[far]) > 0.8
    noise = record.truth["dac"] / math.sqrt(12)
    errors = problem.resolution_errors(params)
    reading = np.sqrt(np.maximum(errors**2 - problem._stop_errors(params) ** 2, 0.0))

    def rms(weights):
        return math.sqrt(np.sum(weights * missed**2) / np.sum(weights))

    # measured 0.0154 against 0.0343 N·m
    assert rms(input_weights(errors, noise, stops=stops)) < 0.6 * rms(
        input_weights(reading, noise))


def _turns_between_plateaus(seed):
    """A gearbox shaft reversing between speed plateaus of 0.4–2 rad/s through raised
    cosines of 0.05–0.15 s, read with 100 counts a turn at 1 kHz (a count takes 30 to
    160 samples): the reading, its force with 0.01 N·m of noise, and its friction."""
    rng = np.random.default_rng(seed)
    t = np.arange(4000) / 1000.0
    times = np.arange(0.5, 4.0, 0.5)
    levels = [0.0] + [(-1.0) ** k * rng.uniform(0.4, 2.0) for k in range(times.size)]
    v = rigzoo.smooth_levels(t, times, levels, rng.uniform(0.05, 0.15))
    x = rigzoo.integrate(t, v)
    truth = {"Fc": 1.4, "Fs": 1.6, "V": 0.03, "delta": 1.7, "s": 220.0, "sigma": 0.3}
    friction = rigzoo.driven_friction(x, v, truth)
    count = 2 * np.pi / 100
    reading = count * np.floor(x / count + rng.uniform())
    F = friction + 0.01 * rng.standard_normal(t.size)
    return cases.dataset("timeseries", {"t": t, "x": reading, "F": F}), truth, friction


def test_a_record_with_other_forces_shares_what_its_motion_sets():
    # a record whose spikes were mended differs only in F: its v, stops and re-readings
    # of x are the record's, its scales and the bounds its forces set are its own
    data, truth, _ = _turns_between_plateaus(2)
    params = {k: v for k, v in truth.items() if k != "sigma"}
    first = Problem(data)
    first.resolution_errors(params)
    mended = with_forces(data, 2.0 * data.columns["F"])
    second = Problem(mended)
    assert second.derivatives is first.derivatives and second.stops == first.stops
    assert second.scales.force == pytest.approx(2.0 * first.scales.force)
    # the re-readings kept from the first (not drawn again) give what a fresh record's
    # give
    errors = second.resolution_errors(params)
    fresh = Problem(replace(mended, columns=dict(mended.columns)))
    assert fresh.derivatives is not first.derivatives
    np.testing.assert_allclose(fresh.resolution_errors(params), errors, rtol=1e-9, atol=1e-12)
    assert np.sqrt(np.mean(errors**2)) > 0.01  # the reading sets an error to compare


@pytest.mark.parametrize("seed", [2, 41])
def test_a_turn_inside_a_count_is_weighed_apart_until_the_record_turns_too(seed):
    # the reading leaves a count back the way it came: the body turned inside it, and
    # its friction flipped there, while the record's direction waits for the reversal
    # hysteresis (three counts) and the model at the truth still slides the old way.
    # The path turned at the stop keeps moving back over those rows, so its errors say
    # how far the friction there may lie from the model's
    data, truth, friction = _turns_between_plateaus(seed)
    problem = Problem(data, ("viscous",))
    missed = np.abs(friction - problem.predict(truth))
    waiting = np.zeros(missed.size, dtype=bool)
    x = problem.recorded_x
    for a, b in problem.stops:
        if np.ptp(x[a:b]) == 0 and 0 < a and b < x.size and x[a - 1] == x[b]:
            turned = np.flatnonzero(problem.d[b:] != problem.d[a])
            waiting[b:b + (turned[0] if turned.size else 0)] = True
    far = waiting & (missed > 0.5 * truth["Fc"])
    assert far.sum() >= 10
    errors = problem._stop_errors(truth)
    # measured 1.0 and 0.95 (0.71 and 0.0 where the turned path took the record's
    # old direction again at the stop's end)
    assert np.mean(errors[far] >= 0.5 * missed[far]) > 0.9


def test_a_rest_at_a_steady_force_is_no_stop_error():
    # strokes one way with rests between, read by an encoder of 25 counts a stroke: the
    # rests are stops, but the force on the body stays put there, so nothing turned
    rng = np.random.default_rng(3)
    t = np.arange(6000) / 1000.0
    x = np.interp(t, [0, 1, 2, 3, 4, 5, 6], [0, 0.01, 0.01, 0.02, 0.02, 0.03, 0.03])
    count = 4e-4
    F = 10.0 + 0.05 * rng.standard_normal(t.size)
    problem = Problem(cases.dataset("timeseries",
                                    {"t": t, "x": np.round(x / count) * count, "F": F}))
    params = BASE_TRUTH["timeseries"]
    assert len(problem.stops) == 3
    errors = problem._stop_errors(params)
    # at the force's noise (0.05 N), where a turn would have moved it by 2 Fc = 20 N
    assert np.sqrt(np.mean(errors**2)) < 0.1
    assert np.max(errors) < 0.2


def test_a_presliding_test_has_no_stops_in_force():
    # a torque sine far below Fs: the body never slides, every row is presliding
    fit = fit_model(parse_csv(machines.families()["presliding-sine"](1).csv))
    assert fit.problem.stops
    assert fit.problem.stop_rows(fit.params) is None
    assert not np.any(fit.problem._stop_errors(fit.params))


def test_a_force_held_late_in_a_warming_record_bounds_the_start_levels():
    # friction that grows 0.5 %/s: a force held late in the record is the start's Fs
    # grown with it, and bounds the start's Fs only once the growth is taken off
    effects = ("viscous", "asymmetry", "drift")
    data, truth = make_dataset("timeseries", effects, seed=7, n=10_000)
    held = Problem(data, effects).held_force(truth)
    assert held[0] <= 1.01 * truth["Fs"] and held[1] <= 1.01 * truth["Fs_neg"]
    # read without the drift, the same record holds more than the start's levels
    steady = {k: v for k, v in truth.items() if k != "alpha"}
    unscaled = Problem(data, effects[:2]).held_force(steady)
    assert unscaled[0] > 1.02 * truth["Fs"] and unscaled[1] > 1.02 * truth["Fs_neg"]


def test_strokes_between_two_ends_break_away_apart_and_spread_turns_do_not():
    # end to end: each direction breaks away at its own end of the travel
    t = np.arange(8000) / 1000.0
    x = 0.01 * (1 - np.cos(2 * np.pi * t / 2.0)) / 2
    ends = Problem(cases.dataset("timeseries", {"t": t, "x": x, "F": np.zeros(t.size)}))
    positive, negative = ends.breakaway_places(BASE_TRUTH["timeseries"])
    assert positive.size == 3 and negative.size == 4
    assert np.all(positive < 1e-4) and np.all(negative > 0.0099)
    assert ends.breakaways_apart(BASE_TRUTH["timeseries"])
    # turning points apart each way but spread along the travel: a stiction that
    # depends on position would vary within each direction's break-aways
    turns = np.array([0.0, -5.0, -1.0, -4.0, 0.0, -3.0, -0.5, -5.0]) * 1e-3
    spread = np.interp(t, np.linspace(0.0, t[-1], turns.size), turns)
    apart = Problem(cases.dataset("timeseries", {"t": t, "x": spread, "F": np.zeros(t.size)}))
    positive, negative = apart.breakaway_places(BASE_TRUTH["timeseries"])
    assert positive.max() < negative.min()
    assert not apart.breakaways_apart(BASE_TRUTH["timeseries"])
    # half-cosine strokes between random turning points: the places mingle
    data, truth = make_dataset("timeseries", ("asymmetry",), seed=7)
    random = Problem(data, ("asymmetry",))
    positive, negative = random.breakaway_places(truth)
    assert positive.size > 5 and negative.size > 5
    assert not random.breakaways_apart(truth)
