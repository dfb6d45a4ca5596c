"""Issue 19: identification that holds on recordings that look like real machines.

Each family of :mod:`tests.identify.machines` is generated for two seeds, written as
the CSV a user would upload, parsed and identified as ``breakaway fit`` does, and its
report checked against the recording's
:class:`~tests.identify.expectations.Expectation` (effects named and none that is not
in the data, warnings, which parameters are determined, values within 10 % where
determined, nothing determined beyond the file's forces and speeds). The generators
themselves are tested first: the quantisation, the printed rounding, the physics.
"""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify import identify, parse_csv
from breakaway.presliding import motion_direction, presliding_force_from_target

from . import machines, machines_classic, plant
from .expectations import Close, Expectation, failures, verdict_params

FAMILIES = machines.families()
SEEDS = (0, 1)
#: Recordings whose report still misses part of what it must say, and what: strict, so
#: that a change that mends one fails here until the entry is removed.
KNOWN_GAPS = {
    ("servo-axis", 0): "residual_structure leads with x (0.10) before x - x_r: this servo "
                       "turns at the ends of its travel, where the presliding misfit sits; "
                       "and offset named in place of asymmetry, as on seed 1: its levels "
                       "differ by nearly one shift (0.0041 and 0.0050 N·m), and it breaks "
                       "away one way at one end of its travel and the other way at the "
                       "other, so the drops' difference may be one of position (§7's "
                       "parsimony names the offset)",
    ("servo-axis", 1): "offset named in place of asymmetry: an offset's one level and an "
                       "asymmetry's two describe the sliding levels of both directions "
                       "alike, and the asymmetry's second Stribeck level does not earn "
                       "its place beside the offset (the family names offset on most "
                       "seeds: 6 of 0-4, 2000, 2001 before the adaptive acceleration "
                       "window, 6 after it, which mends seed 0's effects)",
    ("presliding-ramps", 0): "inertia named (m_e = 210 kg·m², RMSE 3.7 % lower, held-out "
                             "error lower in 8 of 10 blocks): it takes what smoothing the "
                             "20-bit encoder's x leaves at each ramp's corner, through a "
                             "presliding stiffness of ~1e4 N·m/rad; the input floor's draws "
                             "do not hold that bias",
}


@pytest.mark.parametrize("family,seed", list(verdict_params(FAMILIES, lambda _: SEEDS,
                                                            KNOWN_GAPS)))
def test_the_report_says_what_the_recording_holds(family, seed):
    recording = FAMILIES[family](seed)
    report = identify(parse_csv(recording.csv))
    missed = failures(report, recording.expect)
    assert not missed, f"{family} seed {seed}:\n" + "\n".join(missed)


# ---------------------------------------------------------------------------------
# the check itself
# ---------------------------------------------------------------------------------


def _report(effects=(), warnings=(), params=None, determined=None):
    params = params or {"Fc": 1.0, "Fs": 1.5}
    return {"effects": list(effects), "warnings": [
        {"code": c, "parameter": p, "message": m} for c, p, m in warnings],
        "final": {"params": params, "determined": determined or {k: True for k in params}},
        "candidates": {}, "unexplained": False, "residual_structure": [], "noise_floor": 0.1}


def test_the_check_names_every_shortfall():
    expect = Expectation(required=frozenset({"inertia"}), allowed=frozenset({"inertia"}),
                         warnings=(("stick-slip", None),), determined={"V": False},
                         close={"Fc": Close(1.3)}, lower_bound=("Fs", 2.0), force_max=1.2)
    report = _report(effects=["ripple"], params={"Fc": 1.0, "Fs": 1.5, "V": 0.1})
    missed = failures(report, expect)
    assert any(m.startswith("inertia not named") for m in missed)
    assert "ripple named but not in the data" in missed
    assert "no stick-slip warning" in missed
    assert any(m.startswith("V = 0.1 determined") for m in missed)
    assert any(m.startswith("Fc = 1, expected 1.3") for m in missed)
    assert any("bound 2" in m for m in missed)
    assert any(m.startswith("Fs = 1.5 determined above the largest force") for m in missed)


def test_the_check_passes_a_report_that_says_it_all():
    expect = Expectation(warnings=(("beyond-data", "Fs"),), determined={"Fs": False},
                         close={"Fc": Close(1.05)}, lower_bound=("Fs", 1.8), force_max=2.0)
    report = _report(warnings=[("beyond-data", "Fs", "the largest force held without sliding, "
                                "1.81 N, is a lower bound on Fs")],
                     determined={"Fc": True, "Fs": False})
    assert failures(report, expect) == []


# ---------------------------------------------------------------------------------
# the plant
# ---------------------------------------------------------------------------------


def test_a_free_body_falls_as_it_should():
    t = np.linspace(0.0, 1.0, 101)
    p = plant.friction_params(0.0, 0.0, 1.0, 1.0, 1.0, 2.0)
    x, v, _ = plant.run_open_loop(t, np.full(t.size, 3.0), p, 2.0, substeps=1000)
    assert x[-1] == pytest.approx(3.0 / (2 * 2.0), rel=2e-5)
    assert v[-1] == pytest.approx(1.5, rel=1e-9)


def test_slow_presliding_follows_the_cores_e6():
    # a light body under a slow force that loads, unloads and reloads inside presliding:
    # the plant's friction along its own x is the core's (E6') at standstill, d·Fs
    t = np.arange(0.0, 3.0, 1e-3)
    u = np.interp(t, [0.0, 1.0, 2.0, 3.0], [0.0, 1.2, 0.3, 0.9])
    Fs, s = 1.5, 1000.0
    p = plant.friction_params(1.0, Fs, 10.0, 1.0, s, 1e-3)
    x, v, friction = plant.run_open_loop(t, u, p, 1e-3, substeps=50)
    assert np.max(np.abs(friction - u)) < 1e-3 * Fs  # quasi-static: friction holds u
    d = motion_direction(x)
    core = presliding_force_from_target(x, d * Fs, s, direction=d)
    assert np.max(np.abs(core - friction)) < 0.01 * Fs
    inverted = machines.quasistatic_presliding(u, Fs, s)
    assert np.max(np.abs(inverted - x)) < 0.01 / s


# ---------------------------------------------------------------------------------
# the recordings
# ---------------------------------------------------------------------------------


def _columns(recording):
    return parse_csv(recording.csv).columns


def _on_grid(values, step, tolerance):
    ratio = np.asarray(values) / step
    return float(np.max(np.abs(ratio - np.round(ratio)))) <= tolerance


@pytest.mark.parametrize("seed", SEEDS)
def test_servo_records_the_dac_command_and_encoder_counts(seed):
    rec = machines.servo_axis(seed)
    data = parse_csv(rec.csv)
    assert data.meta["units"] == "rotary"
    assert _on_grid(data.columns["F"], machines.SERVO_DAC_STEP, 1e-6)
    assert np.max(np.abs(data.columns["F"])) <= machines.SERVO_AMPLITUDE + 1e-9
    # positions are counts of 2π/10,000 rad, printed to 1e-6 rad
    assert _on_grid(data.columns["x"], rec.truth["count"], 0.5e-6 / rec.truth["count"] + 1e-6)
    h = rec.hidden
    # the plant's balance: J·a = u − friction (each sample's force held over its step),
    # where the body slides and the friction changes little within a step
    a = np.diff(h["v"]) / np.diff(h["t"])
    friction = 0.5 * (h["friction"][1:] + h["friction"][:-1])
    sliding = np.abs(h["v"][1:]) > 1.0
    balance = h["J"] * a - (h["u"][:-1] - friction)
    assert np.max(np.abs(balance[sliding])) < 1e-3 * machines.SERVO_AMPLITUDE
    # inertia dominates; the directions slide at levels 20–30 % apart
    assert np.sqrt(np.mean((h["J"] * a) ** 2)) > 0.5 * rec.truth["Fc"]
    ratio = np.median(h["friction"][h["v"] < -1]) / -np.median(h["friction"][h["v"] > 1])
    assert ratio == pytest.approx(rec.truth["Fc_neg"] / rec.truth["Fc"], rel=0.01)
    assert 0.2 <= abs(ratio - 1) <= 0.3


@pytest.mark.parametrize("exponent", [0.4, 2.0])
def test_joint_curves_are_averaged_set_points(exponent):
    rec = machines.joint_steady(3, exponent)
    data = parse_csv(rec.csv)
    v, F = data.columns["v"], data.columns["F"]
    assert data.meta["units"] == "rotary"
    assert 24 <= np.count_nonzero(v > 0) == np.count_nonzero(v < 0) <= 36
    assert 0.005 <= np.min(np.abs(v)) <= 0.02 and 2.2 <= np.max(np.abs(v)) <= 2.8
    scatter = F - rec.hidden["clean"]
    assert np.std(scatter) < 0.05 * rec.truth["Fc"]
    rise = rec.truth["sigma"] * np.max(np.abs(v)) ** exponent / rec.truth["Fc"]
    assert 0.6 <= rise <= 1.2


@pytest.mark.parametrize("family", ["presliding-ramps", "presliding-sine"])
def test_presliding_records_never_slide(family):
    rec = FAMILIES[family](2)
    h = rec.hidden
    assert np.max(h["u"]) <= h["Fs"] / 3 + 1e-9  # Fs is 3–8 times the largest force
    # the position stays inside presliding: f(s·|x − x_r|) never comes near 1
    assert np.ptp(h["x"]) * rec.truth["s"] < 0.2
    assert np.all(h["u"] >= 0)  # one direction of force
    cols = _columns(rec)
    assert _on_grid(cols["x"], h["count"], 0.1)
    assert abs(np.max(cols["F"]) - rec.truth["held"]) < 1e-3 * rec.truth["held"]


@pytest.mark.parametrize("seed", SEEDS)
def test_stick_slip_really_sticks_and_slips(seed):
    rec = machines.stick_slip_creep(seed)
    v, speed = rec.hidden["v"], rec.truth["speed"]
    assert np.mean(np.abs(v) < 0.05 * speed) > 0.5  # at rest for most of the time
    slipping = np.abs(v) > 10 * speed
    starts = np.flatnonzero(np.diff(slipping.astype(int)) == 1)
    assert starts.size >= 4
    periods = np.diff(starts) / 1000.0
    assert np.std(periods) > 0.01 * np.mean(periods)  # quasi-periodic: an uneven drive
    F = _columns(rec)["F"]
    assert np.ptp(F[2000:]) > 20 * 0.03  # the force oscillates far above the load cell's noise
    assert np.min(np.diff(rec.hidden["x"])) > -0.1 / rec.truth["s"]  # it never runs back


@pytest.mark.parametrize("command", ["ramp", "steps", "controller"])
def test_degrees_are_counts_printed_with_four_decimals(command):
    rec = machines.joint_in_degrees(0, command)
    data = parse_csv(rec.csv)
    x, F = data.columns["x"], data.columns["F"]
    assert _on_grid(x, 1e-4, 1e-6)
    levels = np.unique(x)
    steps = np.round(np.diff(levels), 4)
    q = 360.0 / machines.DEGREE_COUNTS
    assert set(np.unique(steps[steps < 1.5 * q])) <= {0.0878, 0.0879}
    # one count of flicker at rest: a reading that returns within two samples
    counts = rec.hidden["counts"]
    back = (np.diff(counts)[:-1] * np.diff(counts)[1:] < 0) & (np.abs(np.diff(counts, 2)) == 2)
    assert np.count_nonzero(back) >= 5
    assert _on_grid(F, 1e-4, 1e-6)
    if command == "steps":
        runs = np.diff(np.flatnonzero(np.diff(F) != 0))
        assert np.median(runs) >= 9  # held at 20–100 Hz between 1 kHz samples


@pytest.mark.parametrize("rates", [1, 2])
def test_breakaway_repeats_at_one_or_two_rates(rates):
    rec = machines_classic.breakaway_repeats(0, rates)
    cols = _columns(rec)
    assert np.unique(cols["k"]).size == rates
    assert _on_grid(cols["F_ba"], 0.01, 1e-6)
    assert cols["k"].size >= 12 * rates
    assert 0.01 < rec.truth["spread"] / rec.truth["level"] < 0.05


@pytest.mark.parametrize("family", ["feed-one-direction", "strokes-viscous", "strokes-none"])
def test_linear_encoder_records_flicker_on_the_count(family):
    rec = FAMILIES[family](0)
    x = _columns(rec)["x"]
    count = rec.truth["count"]
    assert _on_grid(x - x[0], count, 1e-3)
    dx = np.round(np.diff(x) / count)
    assert np.count_nonzero(dx < 0) > 0 and np.count_nonzero(dx > 0) > 0
    if family == "feed-one-direction":
        # backward steps are single counts of flicker, never a motion
        assert np.min(dx) == -1
        assert np.min(np.diff(rec.hidden["x"])) >= 0


@pytest.mark.parametrize("effect", ["viscous", "offset", "drift"])
def test_stroke_effects_stand_far_above_the_load_cell(effect):
    rec = machines_classic.strokes(0, effect)
    h, truth = rec.hidden, rec.truth
    size = {"viscous": truth.get("sigma", 0) * np.max(np.abs(h["v"])),
            "offset": abs(truth.get("F_offset", 0)),
            "drift": abs(truth.get("alpha", 0)) * (h["t"][-1] - h["t"][0]) * truth["Fc"]}[effect]
    assert size > 5 * 0.08  # the load cell's noise is 0.03–0.08 N


def test_an_unknown_stroke_effect_is_refused():
    with pytest.raises(ValueError, match="no stroke family with 'lag'"):
        machines_classic.strokes(0, "lag")
