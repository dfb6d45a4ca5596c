"""The noise floor is the noise of the measured force alone; what the resolution of x
sets is the input floor, reported beside it."""

from __future__ import annotations

import math

import numpy as np
import pytest

from breakaway.identify import diagnose, identify, parse_csv, report
from breakaway.identify.fitting import fit_model
from breakaway.identify.models import problem_for
from breakaway.identify.input_error import input_floor, input_weights, misfit_ratio
from breakaway.identify.noise import (carried_from_x, difference_sigma, estimate, is_command,
                                      orderings, smooth_sigma)

from . import cases, rigzoo


@pytest.mark.parametrize("count", [2e-6, 2e-5])
def test_an_encoders_steps_do_not_raise_the_noise_floor(count):
    # issue 26: the floor read what x's steps add through the model (0.28 N beside a
    # final RMSE of 0.02 N); it is the load cell's noise, whatever the encoder
    data, truth = cases.encoder_record(seed=1, count=count, F_noise=0.05)
    report = identify(data)
    assert report["noise_floor"] == pytest.approx(0.05, rel=0.25)
    assert 0.0 <= report["input_floor"] <= math.sqrt(
        max(report["error_after"] ** 2 - report["noise_floor"] ** 2, 0.0)) + 1e-12
    assert report["effects"] == []


def test_weights_single_out_the_rows_that_x_s_reading_makes_uncertain():
    rng = np.random.default_rng(0)
    # an encoder's counts: most rows' force does not depend on the count (sliding);
    # those after a reversal do, and count for less than the noise floor's rows
    counted = np.where(rng.random(1000) < 0.1, rng.uniform(0.5, 2.0, 1000), 0.0)
    weights = input_weights(counted, 0.1)
    np.testing.assert_allclose(weights[counted == 0], 1.0)
    assert np.all(weights[counted > 0] < 0.04)
    # x read with continuous noise under a noise-free force: every row has some error,
    # and the fit is not handed to the one row that has the least
    continuous = rng.uniform(0.01, 0.2, 1000)
    weights = input_weights(continuous, 1e-9)
    assert np.mean(weights >= 0.5) >= 0.5
    assert np.min(weights) > 0.01
    assert input_weights(np.zeros(10), 0.1) is None  # exact x


def test_rows_in_stops_set_no_floor_for_the_rest():
    # a servo on a count for 60 % of its record under a noise-free command: the rows
    # where it moves keep their weight, those in the stops lose theirs
    rng = np.random.default_rng(1)
    stops = rng.random(1000) < 0.6
    errors = np.where(stops, rng.uniform(0.5, 2.0, 1000), rng.uniform(0.001, 0.01, 1000))
    apart = input_weights(errors, 1e-6, stops=stops)
    assert np.mean(apart[~stops] >= 0.5) >= 0.5
    assert np.max(apart[stops]) < 1e-3
    # the floor over every row would be a stop's error, and the stops keep much of theirs
    together = input_weights(errors, 1e-6)
    assert np.median(together[stops]) > 0.1


def test_a_coarser_encoder_sets_more_of_the_error():
    fine, _ = cases.encoder_record(seed=2, count=2e-6)
    coarse, _ = cases.encoder_record(seed=2, count=4e-5)
    floors = []
    for data in (fine, coarse):
        fit = fit_model(data)
        floors.append(input_floor(fit, estimate(fit.problem)))
    assert floors[1] > 3 * floors[0]


def _ramp_less_gravity(noise, seed=0, n=3000):
    """A programmed torque ramp less a gravity model of the encoder's angle (the force
    column of an open-loop test on a robot joint), with ``noise`` [N·m] of a sensor."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 0.015
    count = 2 * np.pi / 2**20
    angle = np.round(np.maximum(t - 20.0, 0.0) ** 1.5 * 1e-3 / count) * count
    F = 0.5 * t - 3.0 * np.cos(angle) + noise * rng.standard_normal(n)
    return cases.dataset("timeseries", {"t": t, "x": angle, "F": F})


def test_a_programmed_ramp_less_a_gravity_model_is_a_command():
    data = _ramp_less_gravity(0.0)
    fit = fit_model(data)
    assert is_command(fit.problem, estimate(fit.problem), fit.residual())
    measured = _ramp_less_gravity(0.02)
    fit = fit_model(measured)
    assert not is_command(fit.problem, estimate(fit.problem), fit.residual())


@pytest.mark.parametrize("hum_hz,phase", [(50.0, 1.4), (60.0, 0.3)])
def test_mains_hum_sampled_at_100_hz_is_not_read_as_three_times_its_size(hum_hz, phase):
    # 50 Hz logged at 100 Hz alternates from row to row: second differences saw it at
    # 2.4 times its RMS (a floor of 0.178 N·m for 0.0093 of noise and 0.074 of hum)
    from breakaway.identify.models import problem_for
    from breakaway.identify.synthetic import make_dataset, with_force

    data, _ = make_dataset("timeseries", (), seed=2, noise=0.0, n=6000)
    t = np.asarray(data.columns["t"])
    t = np.arange(t.size) / 100.0
    rng = np.random.default_rng(5)
    white, hum = 0.01, 0.075
    F = np.asarray(data.columns["F"]) + white * rng.standard_normal(t.size) \
        + hum * np.sin(2 * math.pi * hum_hz * t + phase)
    data = with_force(data, F)
    data.columns["t"] = t
    floor = estimate(problem_for(data)).value
    assert white / 1.5 <= floor <= 1.5 * math.hypot(white, hum / math.sqrt(2))


def _swing_less_gravity(sensor_noise, seed=0, n=4000, counts=1024):
    """A joint swinging slowly (under a count a row) and its force column: the
    programme less a gravity model of the encoder's reading (``sensor_noise`` = 0), or
    the true force read by a sensor with ``sensor_noise`` [N·m]. Returns the dataset
    and the std [N·m] of what the reading's steps put into the column."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / 500.0
    count = 2 * np.pi / counts
    angle = 0.6 * np.sin(2 * np.pi * 0.2 * t + rng.uniform(0, 2 * np.pi))
    reading = np.round(angle / count) * count
    programme = 2.0 * np.sin(2 * np.pi * 0.13 * t)
    true = programme - 3.0 * np.sin(angle)
    if sensor_noise == 0:
        F = programme - 3.0 * np.sin(reading)
    else:
        F = true + sensor_noise * rng.standard_normal(n)
    return cases.dataset("timeseries", {"t": t, "x": reading, "F": F}), float(np.std(F - true))


def test_a_force_computed_from_the_encoders_reading_carries_its_steps():
    # issue 26: a programmed torque less a gravity model steps by g'(x)·count wherever
    # the reading ticks; between ticks it is smooth, so differences read only its
    # printed digits (3.3e-5 N·m beside 4e-3 N·m that the column carries)
    from breakaway.identify.models import problem_for

    data, carried = _swing_less_gravity(0.0)
    noise = estimate(problem_for(data))
    assert noise.method == "carried from x"
    assert carried / 1.5 <= noise.value <= 1.5 * carried
    assert carried_from_x(problem_for(data)) == pytest.approx(noise.value)


def test_a_measured_force_is_as_rough_where_the_reading_ticks_as_between():
    from breakaway.identify.models import problem_for

    data, _ = _swing_less_gravity(0.003)
    noise = estimate(problem_for(data))
    assert carried_from_x(problem_for(data)) == 0.0
    assert noise.method == "differences"
    assert noise.value == pytest.approx(0.003, rel=0.2)


def test_a_steady_curves_floor_is_no_more_than_a_smooth_fit_leaves():
    # a gearbox's σ·|v|^2.2 over 13 geometric set-points a direction: differences across
    # the last, widely spaced ones read the curve's bend as noise (2.2× the scatter)
    record = rigzoo.gearbox_steady(2000)
    problem = problem_for(parse_csv(record.csv))
    floor = estimate(problem)
    scatter = record.truth["scatter"]
    assert difference_sigma(problem.measured, orderings(problem)) > 2.0 * scatter
    assert floor.method == "smooth fit"
    assert floor.value == pytest.approx(scatter, rel=0.3)


def test_a_smooth_fit_does_not_lower_a_floor_that_differences_read_right():
    # a straight curve with dense set-points: differences are unbiased, and the smooth
    # fit, no better, leaves them the floor (a minimum of estimates must not run low)
    rng = np.random.default_rng(4)
    v = np.concatenate([np.linspace(0.01, 1.0, 60), -np.linspace(0.01, 1.0, 60)])
    F = np.sign(v) * (1.0 + 0.3 * np.abs(v)) + 0.02 * rng.standard_normal(v.size)
    text = "v,F\n" + "\n".join(f"{a:.6g},{b:.6g}" for a, b in zip(v, F))
    floor = estimate(problem_for(parse_csv(text)))
    assert floor.value == pytest.approx(0.02, rel=0.25)
    assert smooth_sigma(problem_for(parse_csv(text))) == pytest.approx(0.02, rel=0.25)


def test_structure_behind_a_few_rows_that_the_reading_makes_uncertain_is_unexplained():
    # a seal whose friction depends smoothly on position, read by a coarse encoder: x's
    # reading sets newtons just after each reversal and nothing elsewhere; against the
    # record's RMS (10.5 N beside an input floor of 10.1 N) the position dependence hid
    record = rigzoo.families()["seal-drift"](2002)
    diagnosis = diagnose(parse_csv(record.csv))
    final, noise = diagnosis.final, diagnosis.noise
    errors = final.problem.resolution_errors(final.params)
    assert final.rmse < 1.3 * math.hypot(noise.value, diagnosis.input_floor)
    assert misfit_ratio(final, noise, diagnosis.input_floor, errors) > 3.0
    assert report(diagnosis)["unexplained"] is True


def test_a_flat_record_read_by_a_coarse_encoder_is_not_unexplained():
    # strokes of a dry slide, nothing outside the model: each row's misfit is what its
    # reading and the load cell make of it
    record = rigzoo.families()["flat-timeseries"](2002)
    diagnosis = diagnose(parse_csv(record.csv))
    errors = diagnosis.final.problem.resolution_errors(diagnosis.final.params)
    ratio = misfit_ratio(diagnosis.final, diagnosis.noise, diagnosis.input_floor, errors)
    assert 0.8 < ratio < 1.3
    assert report(diagnosis)["unexplained"] is False


def test_a_controllers_output_is_read_as_computed_from_x_by_the_normal_equations():
    # computed_from_x solves the 16-column regression by its normal equations (an SVD
    # of the tall matrix took a second on a million rows): its R² is the tall
    # least-squares fit's, for a PD output of the encoder's counts and for a sensor
    from breakaway.identify.local_fits import smooth_fit
    from breakaway.identify.noise import CONTROLLER_LAGS, FAST_WINDOW, computed_from_x

    rng = np.random.default_rng(3)
    t = np.arange(20_000) * 1e-3
    count = 2 * np.pi / 4096
    x = np.round(0.3 * np.sin(2 * np.pi * 0.4 * t) / count) * count
    pd_output = 40.0 * (0.1 * np.sin(t) - x) - 0.8 * np.gradient(x, t)
    sensor = np.sign(np.cos(2 * np.pi * 0.4 * t)) + 0.01 * rng.standard_normal(t.size)
    for F, computed in ((pd_output, True), (sensor, False)):
        lags = CONTROLLER_LAGS
        x_fast = x - smooth_fit(t, x, FAST_WINDOW)[0]
        F_fast = (F - smooth_fit(t, F, FAST_WINDOW)[0])[lags:]
        tall = np.column_stack([x_fast[lags - k:x.size - k] for k in range(lags)])
        coef, *_ = np.linalg.lstsq(tall, F_fast, rcond=None)
        r2 = 1.0 - np.var(F_fast - tall @ coef) / np.var(F_fast)
        assert computed_from_x(t, x, F) == pytest.approx(r2, abs=1e-9)
        assert (r2 >= 0.9) == computed
