"""Kinematics of measured positions: quantisation, reversals with hysteresis, velocity."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify.derivatives import velocity
from breakaway.identify.kinematics import direction, position_noise, printed_unit, quantum
from breakaway.identify.synthetic import displacement_excitation
from breakaway.presliding import motion_direction


@pytest.fixture(scope="module")
def strokes():
    return displacement_excitation(np.random.default_rng(4), 6000)


def test_exact_positions_follow_model_md_section_3(strokes):
    t, x = strokes
    assert quantum(x) == 0.0
    assert position_noise(x) == 0.0
    np.testing.assert_array_equal(direction(x, 0.0), motion_direction(x))
    np.testing.assert_array_equal(velocity(t, x, 0.0), np.gradient(x, t))


@pytest.mark.parametrize("count", [1e-6, 5e-6, 2.5e-5])
def test_an_encoder_step_is_found(strokes, count):
    _, x = strokes
    assert quantum(np.round(x / count) * count) == pytest.approx(count, rel=1e-6)


@pytest.mark.parametrize("decimals", [3, 4, 5])
def test_counts_converted_to_degrees_and_printed_are_still_a_step(decimals):
    # a 4096-count encoder logged in degrees: the gaps are q ± the printed rounding
    count = 360 / 4096
    rng = np.random.default_rng(decimals)
    counts = np.cumsum(rng.integers(-1, 3, 4000))
    printed = np.round(counts * count, decimals)
    assert printed_unit(printed) == pytest.approx(10.0 ** -decimals)
    assert quantum(printed) == pytest.approx(count, rel=1e-4)


@pytest.mark.parametrize("counts_per_turn", [16_384, 40_000, 65_536])
def test_degrees_printed_then_converted_to_rad_are_still_a_step(counts_per_turn):
    # counts logged in degrees with four decimals, then converted to rad: no printed
    # digit of the rad column shows the rounding, but the one-count gaps come as two
    # values a rounding unit apart (3 and 4 units for a count of 3.5 units)
    count_deg = 360 / counts_per_turn
    rng = np.random.default_rng(counts_per_turn)
    counts = np.cumsum(rng.integers(-1, 3, 3000))
    counts[2000:] += np.cumsum(rng.integers(0, 300, 1000))  # slips of many counts
    rad = np.deg2rad(np.round(counts * count_deg, 4))
    assert printed_unit(rad) < 1e-4 * np.deg2rad(count_deg)
    assert quantum(rad) == pytest.approx(np.deg2rad(count_deg), rel=1e-3)


@pytest.mark.parametrize("count", [2e-6, 2e-5, 5e-6])
def test_a_step_of_two_or_five_printed_units_is_the_data_s_own(strokes, count):
    # a 2 µm or 5 µm scale, a 20 µm count, logged in m with seven decimals: the finest
    # power of ten every value sits on is 1e-6 or 1e-5, and the values sit on every
    # second (fifth) one only, which rounding to the printed digits never does
    _, x = strokes
    logged = np.round(np.round(x / count) * count, 7)
    assert printed_unit(logged) < count
    assert quantum(logged) == pytest.approx(count, rel=1e-6)


def test_a_one_micrometre_scale_logged_with_seven_decimals_is_a_step(strokes):
    # the values sit on every 1e-6, as digits printed to 1e-6 would: only the file's
    # text, printed to 1e-7, tells the scale's step from the logger's rounding
    from breakaway.identify import parse_csv
    from breakaway.identify.models import problem_for

    t, x = strokes
    x = 100 * x  # fast strokes: many counts between samples
    rng = np.random.default_rng(0)
    counts = np.round(x / 1e-6)
    rows = [f"{a:.4f},{c * 1e-6:.7f},{10 * np.sign(b) + 0.1 * rng.standard_normal():.4f}"
            for a, c, b in zip(t, counts, np.gradient(x))]
    data = parse_csv("t [s],x [m],F [N]\n" + "\n".join(rows))
    assert data.printed["x"] == pytest.approx(1e-7)
    assert printed_unit(data.columns["x"]) == pytest.approx(1e-6)
    assert problem_for(data).quantum_x == pytest.approx(1e-6, rel=1e-6)
    assert quantum(data.columns["x"]) == 0.0  # the digits alone cannot tell


def test_printed_unit_and_a_continuous_column():
    rng = np.random.default_rng(2)
    walk = np.cumsum(rng.standard_normal(5000)) * 1e-3
    assert printed_unit(walk) == 0.0  # full double precision
    assert printed_unit(np.round(walk, 6)) == pytest.approx(1e-6)
    # a continuous column printed with 6 decimals is not a step of 1e-6: its changes
    # are hundreds of units
    assert quantum(np.round(walk, 6)) == 0.0
    assert printed_unit(np.array([1500.0, 2500.0])) == pytest.approx(100.0)


def test_jitter_of_one_count_is_no_reversal(strokes):
    t, x = strokes
    count = 2e-6
    rng = np.random.default_rng(0)
    jittered = (np.round(x / count) + rng.integers(-1, 2, x.size)) * count
    d = direction(jittered, 3 * count)
    exact = motion_direction(x)
    assert np.count_nonzero(np.diff(d)) == np.count_nonzero(np.diff(exact))
    # reversals land within a few samples of the true ones
    true_turns = np.flatnonzero(np.diff(exact))
    found = np.flatnonzero(np.diff(d))
    assert np.max(np.abs(found - true_turns)) <= 40


def test_slow_motion_is_timed_over_several_counts(strokes):
    t, x = strokes
    count = 2e-6
    q = np.round(x / count) * count
    plain = np.gradient(q, t)
    adaptive = velocity(t, q, count)
    exact = np.gradient(x, t)
    # measured: 0.48 of the plain gradient's error on this record
    assert np.sqrt(np.mean((adaptive - exact) ** 2)) < 0.6 * np.sqrt(np.mean((plain - exact) ** 2))


def test_noise_in_x_is_measured(strokes):
    _, x = strokes
    noisy = x + 2e-6 * np.random.default_rng(1).standard_normal(x.size)
    assert position_noise(noisy) == pytest.approx(2e-6, rel=0.15)
