"""The loop view's numbers (breakaway.loop): hunting, settling, stick phases beside
(E13), the RMS error and what compensation does to it (MODEL.md §5b)."""

import math

import numpy as np
import pytest

from breakaway.dynamics.common import EVENT_BREAKAWAY, EVENT_REVERSAL, EVENT_STICK
from breakaway.loop import hunting, loop_experiment, phase_e13, rms_error, stick_phases
from breakaway.params import LOOP_DEFAULTS, LUGRE_1995
from breakaway.quasistatic import breakaway_force

PLANT = dict(Fc=1.0, Fs=1.5, V=100.0, delta=1.0, sigma=0.0, s=1.0, m=1e-5, z_ba=0.95)
PID = {name: LOOP_DEFAULTS["presliding"][name] for name in ("Kp", "Ki", "Kd", "u_max")}
STEP = {"kind": "step", "h": 10.0}
SINE = {"kind": "sine", "h": 10.0, "f": 0.5}


def run(plant=PLANT, controller=PID, reference=STEP, model="presliding", **kwargs):
    return loop_experiment(model, plant, controller, reference, 5.0, **kwargs)


# ---------------------------------------------------------------------------------
# hunting (Fs > Fc with integral action) and settling (Fs = Fc)
# ---------------------------------------------------------------------------------


VARIANTS = [PID, {**PID, "Ki": 2.0}, {**PID, "Ki": 5.0}]


@pytest.mark.parametrize("controller", VARIANTS)
def test_stiction_and_integral_action_hunt(controller):
    out = run(controller=controller)
    hunt = out["hunting"]
    assert hunt is not None and hunt["count"] >= 3
    late = [p for p in out["stick_phases"] if p["t_ba"] >= 2.5]
    assert hunt["period"] == pytest.approx(np.mean(np.diff([p["t_ba"] for p in late])))
    # the cycle: a stick on either side of the target, breaking away in turn
    assert {p["direction"] for p in late} == {-1, 1}
    assert hunt["cycle"] == pytest.approx(2 * hunt["period"], rel=0.1)
    assert 0.2 < hunt["amplitude"] < 10.0


def test_default_loop_hunts_as_documented():
    """params.LOOP_DEFAULTS says: ±1.8 around the target, a break-away every 0.65 s."""
    hunt = run()["hunting"]
    assert hunt["period"] == pytest.approx(0.645, abs=0.01)
    assert hunt["amplitude"] == pytest.approx(1.88, abs=0.05)


@pytest.mark.parametrize("controller", VARIANTS)
def test_without_stiction_the_same_loop_settles_within_its_band(controller):
    out = run(plant={**PLANT, "Fs": 1.0}, controller=controller)
    assert out["hunting"] is None
    t, e = out["t"], out["e"]
    band = 0.02 * STEP["h"]  # the usual 2 % settling band
    assert np.max(np.abs(e[t >= 2.5])) < band


@pytest.mark.parametrize("Kd", [0.004, 0.01, 0.02])
def test_more_damping_stops_the_hunting(Kd):
    """Kd near the Stribeck curve's steepest fall (Fs − Fc)/V = 0.005 N·s/m and above:
    the slips no longer run away from the friction, and the loop settles."""
    assert run(controller={**PID, "Kd": Kd})["hunting"] is None


def test_lugre_loop_hunts_and_settles_without_stiction():
    d = LOOP_DEFAULTS["lugre"]
    controller = {name: d[name] for name in ("Kp", "Ki", "Kd", "u_max")}
    step = {"kind": "step", "h": d["h"]}
    hunt = run({"z_ba": 0.95}, controller, step, model="lugre")["hunting"]
    assert hunt is not None and hunt["period"] == pytest.approx(0.40, abs=0.02)
    settled = run({"z_ba": 0.95, "Fs": 1.0}, controller, step, model="lugre")
    assert settled["hunting"] is None
    assert np.max(np.abs(settled["e"][settled["t"] >= 2.5])) < 0.01 * d["h"]


# ---------------------------------------------------------------------------------
# compensation
# ---------------------------------------------------------------------------------


def test_exact_compensation_halves_the_error_of_a_sine():
    """With Kd above the Stribeck fall the body follows ṙ, and c·Fss(ṙ) with c = 1
    cancels the friction it meets (RMS 2.47 → 0.40)."""
    controller = {**PID, "Kd": 0.01}
    none = run(controller=controller, reference=SINE)["rms_error"]
    exact = run(controller=controller, reference=SINE,
                compensation={"scale": 1.0})["rms_error"]
    assert exact < 0.5 * none
    half = run(controller=controller, reference=SINE, compensation={"scale": 0.5})["rms_error"]
    assert exact < half < none


def test_compensation_does_not_help_a_loop_that_cannot_follow():
    """At the default Kd (below the Stribeck fall) the body sticks and slips instead of
    following ṙ: friction compensation from ṙ makes the error larger, as
    params.LOOP_DEFAULTS says."""
    none = run(reference=SINE)["rms_error"]
    exact = run(reference=SINE, compensation={"scale": 1.0})["rms_error"]
    assert exact > none


def test_a_wrong_model_compensates_worse_than_the_right_one():
    controller = {**PID, "Kd": 0.01}
    right = run(controller=controller, reference=SINE, compensation={"scale": 1.0})
    wrong = run(controller=controller, reference=SINE,
                compensation={"scale": 1.0, "params": {"Fc": 0.5, "Fs": 0.6}})
    assert wrong["rms_error"] > 1.5 * right["rms_error"]


# ---------------------------------------------------------------------------------
# stick phases beside (E13)
# ---------------------------------------------------------------------------------


def test_each_phase_carries_e13_at_its_own_rate():
    out = run()
    phases = out["stick_phases"]
    assert len(phases) >= 8
    for phase in phases:
        k = phase["direction"] * (phase["u_ba"] - phase["u_start"]) / (
            phase["t_ba"] - phase["t_start"])
        assert phase["k"] == pytest.approx(k, rel=1e-12)
        if k > 0:
            e13 = float(breakaway_force(k, 1.0, 1.5, 100.0, 1.0, 1.0, 0.0, "avg", 0.95))
            assert phase["E13"] == pytest.approx(phase["direction"] * e13, rel=1e-12)
            # the simulated break-away is shown beside E13, not forced onto it: in this
            # loop the body slips at a higher u than E13's (inertia, ∂F/∂ẋ·ẍ of §5)
            assert abs(phase["u_ba"]) > abs(phase["E13"])
        else:
            assert phase["E13"] is None
        assert phase["t_start"] < phase["t_ba"]
        assert np.sign(phase["u_ba"]) == phase["direction"]


def test_phases_are_at_the_recorded_events():
    out = run()
    t = out["t"]
    for phase in out["stick_phases"]:
        i = np.flatnonzero(t == phase["t_ba"])
        assert i.size == 1 and out["u"][i[0]] == phase["u_ba"] and out["F"][i[0]] == phase["F_ba"]


def test_e13_of_a_lugre_phase_uses_its_bristles_as_presliding_distance():
    d = LOOP_DEFAULTS["lugre"]
    controller = {name: d[name] for name in ("Kp", "Ki", "Kd", "u_max")}
    out = run({"z_ba": 0.95}, controller, {"kind": "step", "h": d["h"]}, model="lugre",
              F_hat="Fs")
    q = LUGRE_1995
    phase = out["stick_phases"][-1]
    e13 = breakaway_force(phase["k"], q["Fc"], q["Fs"], q["vs"], q["delta"],
                          q["sigma0"] / q["Fs"], q["sigma2"], "Fs", 0.95)
    assert phase["E13"] == pytest.approx(phase["direction"] * float(e13), rel=1e-12)


def test_stick_phases_from_events():
    t = np.arange(8.0)
    u = np.array([0.0, 1.0, 2.0, 3.0, 1.0, 0.0, -2.0, -3.0])
    v = np.array([0.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0, -5.0])
    code = np.zeros(8, dtype=int)
    code[3] = EVENT_BREAKAWAY
    code[4] = EVENT_REVERSAL  # a reversal while sliding back is not a new phase...
    code[4] |= EVENT_STICK  # ... unless it is the first after a break-away
    code[5] = EVENT_REVERSAL
    code[7] = EVENT_BREAKAWAY
    phases = stick_phases(t, u, v, u, code)
    np.testing.assert_array_equal(phases["t_start"], [0.0, 4.0])
    np.testing.assert_array_equal(phases["t_ba"], [3.0, 7.0])
    np.testing.assert_array_equal(phases["direction"], [1.0, -1.0])
    np.testing.assert_allclose(phases["k"], [1.0, 4.0 / 3.0])


def test_a_phase_still_sticking_at_the_end_is_not_reported():
    code = np.array([0, EVENT_BREAKAWAY, EVENT_STICK, 0])
    phases = stick_phases(np.arange(4.0), np.ones(4), np.ones(4), np.ones(4), code)
    assert phases["t_ba"].tolist() == [1.0]


def test_e13_is_not_given_where_u_did_not_ramp_towards_the_breakaway():
    steady = dict(Fc=1.0, Fs=1.5, V=100.0, delta=1.0, sigma=0.0)
    out = phase_e13(np.array([2.0, -1.0, np.nan]), np.array([-1.0, 1.0, 1.0]), steady, 1.0,
                    "avg", 0.95)
    assert out[0] == pytest.approx(-float(breakaway_force(2.0, 1.0, 1.5, 100.0, 1.0)))
    assert np.isnan(out[1]) and np.isnan(out[2])


# ---------------------------------------------------------------------------------
# hunting and RMS as functions
# ---------------------------------------------------------------------------------


def test_hunting_needs_two_breakaways_in_the_last_half():
    t = np.linspace(0.0, 10.0, 101)
    assert hunting([1.0, 2.0, 6.0], [1, -1, 1], t, np.sin(t), 10.0) is None
    hunt = hunting([1.0, 5.0, 6.0, 7.5, 9.0], [1, 1, -1, 1, -1], t, 3.0 * np.sin(t), 10.0)
    # late: 5 (+), 6 (−), 7.5 (+), 9 (−)
    assert hunt["period"] == pytest.approx(4.0 / 3.0)
    assert hunt["count"] == 4
    assert hunt["cycle"] == pytest.approx((2.5 + 3.0) / 2)
    late = t >= 5.0
    assert hunt["amplitude"] == pytest.approx(0.5 * np.ptp(3.0 * np.sin(t[late])))


def test_rms_error_of_a_sine_is_its_amplitude_over_root_two():
    t = np.linspace(0.0, 10.0, 10_001)
    assert rms_error(t, 2.0 * np.sin(2 * math.pi * t)) == pytest.approx(2.0 / math.sqrt(2), rel=1e-6)
    assert math.isnan(rms_error([0.0], [1.0]))
