"""Stick-slip in a time series (MODEL.md §8 ``stick-slip``) and the ripple it is not."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify import diagnose, parse_csv, report
from breakaway.identify.effects import EFFECTS
from breakaway.identify.fitting import fit_model
from breakaway.identify.stickslip import find_stick_slip
from breakaway.identify.synthetic import make_dataset, with_force

from .machines import stick_slip_creep
from .machines_classic import feed_one_direction, strokes


def _columns(recording):
    data = parse_csv(recording.csv)
    return data, (data.columns["t"], data.columns["x"], data.columns["F"])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_stage_dragged_through_a_spring_sticks_and_slips(seed):
    recording = stick_slip_creep(seed)
    _, columns = _columns(recording)
    cycle = find_stick_slip(*columns)
    assert cycle is not None and cycle.cycles >= 4
    # the true velocity rests (below 5 % of its slip speed) as long as the record says
    speed = np.abs(recording.hidden["v"])
    rest = speed < 0.05 * np.percentile(speed, 99)
    assert cycle.rest_share == pytest.approx(float(np.mean(rest)), abs=0.05)
    # the drive advances one slip's travel per period
    assert cycle.travel == pytest.approx(recording.truth["speed"] * cycle.period, rel=0.3)


@pytest.mark.parametrize("make", [feed_one_direction, strokes])
@pytest.mark.parametrize("seed", [0, 1])
def test_a_feed_that_stops_and_strokes_that_turn_do_not_stick_and_slip(make, seed):
    _, columns = _columns(make(seed))
    assert find_stick_slip(*columns) is None


def test_the_report_says_stick_slip_and_takes_no_ripple_at_its_wavelength():
    data, _ = _columns(stick_slip_creep(1))
    result = report(diagnose(data))
    [entry] = [w for w in result["warnings"] if w["code"] == "stick-slip"]
    assert "stick phases" in entry["message"] and "a slip every" in entry["message"]
    assert "ripple" not in result["effects"]
    # a ripple fitted at the cycle's travel is refused as the cycle
    problem = fit_model(data).problem
    cycle = problem.stick_slip
    reason = EFFECTS["ripple"].unresolved(problem, {
        "A": 1.0, "wavelength": cycle.travel, "phase": 0.0, **fit_model(data).params})
    assert reason.startswith("stick-slip")


def test_a_ripple_must_hold_its_phase_across_the_travel():
    data, truth = make_dataset("timeseries", ("ripple",), seed=11, n=10_000)
    locked = report(diagnose(data))
    assert locked["effects"] == ["ripple"]
    # the same ripple with its phase turned by half a period in the upper half of the
    # travel: no position-locked friction does that
    x = data.columns["x"]
    middle = 0.5 * (x.min() + x.max())
    wave = truth["A"] * np.sin(2 * np.pi * x / truth["wavelength"] + truth["phase"])
    flipped = data.columns["F"] - 2 * np.where(x >= middle, wave, 0.0)
    result = report(diagnose(with_force(data, flipped)))
    assert "ripple" not in result["effects"]
    assert "does not hold across the travel" in result["candidates"]["ripple"]["reason"]
