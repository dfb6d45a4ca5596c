"""The plan as a whole: it never asks a rig for more than its limits, proposes nothing
for what is determined, and says what a family cannot do and which family can."""

import copy
import io

import numpy as np
import pytest

from breakaway.plan import PlanError, plan_experiment

from .records import high_rates, steady, timeseries

#: Parameter sets and limits the limits are checked over (a seeded spread of rigs).
RIGS = [dict(params={"Fc": 1.0, "Fs": 1.5, "V": 100.0, "delta": 1.0}, limits={}),
        dict(params={"Fc": 2.0, "Fs": 3.0, "V": 2e-3, "delta": 2.0, "s": 5e4, "sigma": 20.0},
             limits={"u_max": 3.5, "v_max": 0.01, "travel": 1e-3}),
        dict(params={"Fc": 0.3, "Fs": 0.9, "V": 0.05, "delta": 0.7, "s": 2000.0},
             limits={"u_max": 1.0, "v_max": 0.2, "v_min": 1e-3, "duration": 5.0})]


def _rows(programme):
    lines = [line for line in programme.splitlines() if not line.startswith("#")]
    body = "\n".join(lines[1:])
    return np.loadtxt(io.StringIO(body), delimiter=",", ndmin=2) if body else np.empty((0, 0))


@pytest.mark.parametrize("rig", RIGS)
def test_no_force_above_u_max_and_no_speed_above_v_max(rig):
    ramps = plan_experiment("ramps", params=rig["params"], limits=rig["limits"])
    limits = ramps["limits"]
    assert max(ramps["design"]["end_force"]) <= limits["u_max"]
    assert np.max(_rows(ramps["programme"])[:, 2]) <= limits["u_max"] * (1 + 1e-8)
    assert max(ramps["design"]["breakaway_speed"]) <= limits["v_max"] * (1 + 1e-9)
    assert max(ramps["design"]["predicted_F_ba"]) < limits["u_max"]
    sets = plan_experiment("steady", params=rig["params"], limits=rig["limits"])
    speeds = np.abs(_rows(sets["programme"])[:, 1])
    assert speeds.max() <= sets["limits"]["v_max"] * (1 + 1e-9)
    assert speeds.min() >= sets["limits"]["v_min"] * (1 - 1e-9)
    assert max(sets["design"]["predicted_F"]) <= sets["limits"]["u_max"]
    sine = plan_experiment("sine", params=rig["params"], limits=rig["limits"])
    if sine["design"] is not None:
        design = sine["design"]
        assert design["peak_speed"] <= sine["limits"]["v_max"] * (1 + 1e-9)
        assert design["peak_force"] <= sine["limits"]["u_max"]
        if sine["limits"]["travel"] is not None:
            assert 2 * design["amplitude"] <= sine["limits"]["travel"] * (1 + 1e-12)
            assert np.ptp(_rows(sine["programme"])[:, 1]) <= sine["limits"]["travel"] * (1 + 1e-9)


def test_a_plan_for_what_is_determined_says_so_and_proposes_nothing():
    _, report = timeseries()
    assert all(report["final"]["determined"].values())
    plan = plan_experiment("sine", report=report)
    assert plan["design"] is None and plan["targets"] == []
    assert _rows(plan["programme"]).size == 0
    assert "Nothing new to measure" in " ".join(plan["notes"])
    for name in ("Fc", "Fs", "V", "delta", "s"):
        entry = plan["predicted"][name]
        assert entry["determined_now"] and entry["stderr_after"] == entry["stderr_now"]
    asked = plan_experiment("ramps", report=report, targets=["V"])
    assert asked["design"] is None
    assert any(note.startswith("V is already determined by the data (V = ") for note in asked["notes"])


def test_ramps_at_high_rates_get_a_plan_over_the_open_range():
    _, report = high_rates()
    plan = plan_experiment("ramps", report=report, limits={"u_max": 3.0})
    assert plan["targets"] == ["Fs", "V", "delta"]
    rates = np.asarray(plan["design"]["rates"])
    low, high = report["extent"]["rates"]
    # the old rates show Fc only: the plan goes far below them, where F_ba falls
    assert rates.min() < low / 100 and np.median(rates) < low
    V = plan["predicted"]["V"]
    assert V["stderr_now"] is None and V["determined_after"]
    assert len(V["across"]) == 5
    assert all(point["determined_after"] for point in V["across"])
    assert all(point["stderr_after"] < 0.2 * point["value"] for point in V["across"])


def test_break_away_alone_cannot_separate_V_from_s_and_the_sine_can():
    _, report = timeseries()
    report = copy.deepcopy(report)
    for name in ("V", "s"):
        report["final"]["determined"][name] = False
        report["final"]["stderr"][name] = None
    plan = plan_experiment("ramps", report=report, targets=["V"],
                           limits={"u_max": 30.0, "v_max": 1.0, "duration": 60.0})
    note = next(n for n in plan["notes"] if n.startswith("Within these limits no ramps plan"))
    assert "only through s·V" in note and "A sine plan would determine it" in note
    assert not plan["predicted"]["V"]["determined_after"]


def test_set_points_cannot_show_s_or_a_drop_below_the_slowest_speed_held():
    _, report = high_rates()
    plan = plan_experiment("steady", report=report, targets=["s", "V"],
                           ranges={"s": (0.5, 2.0)}, limits={"v_min": 50.0, "u_max": 3.0})
    notes = " ".join(plan["notes"])
    assert "The steady curve does not depend on the presliding scale s" in notes
    assert "below the slowest speed the rig holds (v_min = 50" in notes
    # set-points cannot reach the drop: the plan names the runs that can (presliding data:
    # slow ramps, or a sine through reversals)
    assert plan["notes"][-1].endswith("it needs presliding data (ramps at slow rates, whose "
                                      "break-away speed goes far lower, or a sine through "
                                      "reversals).")


def test_a_force_limit_below_the_breakaway_level_yields_no_ramps():
    _, report = high_rates()
    plan = plan_experiment("ramps", report=report, limits={"u_max": 0.5})
    assert plan["design"] is None
    assert "no ramp breaks away below u_max = 0.5" in " ".join(plan["notes"])


def test_a_steady_record_needs_a_range_for_s_before_a_sine():
    _, report = steady()
    with pytest.raises(PlanError) as caught:
        plan_experiment("sine", report=report)
    assert caught.value.path == ("ranges", "s")
    plan = plan_experiment("sine", report=report, ranges={"s": (500.0, 8000.0)},
                           limits={"travel": 0.01, "duration": 5.0, "u_max": 25.0})
    assert "s" in plan["targets"] and plan["predicted"]["s"]["determined_after"]


@pytest.mark.parametrize("kwargs, path", [
    (dict(family="walk", params={}), ("family",)),
    (dict(family="ramps"), ("params",)),
    (dict(family="ramps", params={}, runs=0), ("runs",)),
    (dict(family="ramps", params={}, targets=["W"]), ("targets", 0)),
    (dict(family="ramps", params={}, limits={"u_max": -1.0}), ("limits", "u_max")),
    (dict(family="ramps", params={}, limits={"v_min": 5.0, "v_max": 1.0}), ("limits", "v_min")),
    (dict(family="ramps", params={}, noise=float("nan")), ("noise",)),
])
def test_bad_requests_are_refused_naming_the_field(kwargs, path):
    with pytest.raises(PlanError) as caught:
        plan_experiment(**kwargs)
    assert caught.value.path == path


def test_the_sine_is_one_record_and_says_runs_do_not_apply():
    plan = plan_experiment("sine", params={"Fc": 1.0, "Fs": 1.5, "V": 10.0}, runs=5)
    assert plan["design"]["runs"] == 1
    assert "The sine is one record of 60 s: runs = 5 does not apply." in plan["notes"]
