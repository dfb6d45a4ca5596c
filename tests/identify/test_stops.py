"""Stops of an encoder's reading (:mod:`breakaway.identify.stops`), on seeded paths."""

import numpy as np
import pytest

from breakaway.identify.kinematics import REVERSAL_STEPS
from breakaway.identify.stops import find_stops, stop_bounds, stop_mask

COUNT = 1e-3


def _read(x):
    return COUNT * np.round(np.asarray(x) / COUNT)


def _strokes_with_a_rest(rest_samples=400, seed=0):
    """10 counts out at a count per 5 samples, a rest flickering on one count boundary,
    then 10 counts on: (the reading, the rest's [start, stop))."""
    rng = np.random.default_rng(seed)
    out = np.arange(50) * COUNT / 5
    boundary = out[-1] + COUNT / 2
    rest = boundary + 0.3 * COUNT * rng.uniform(-1, 1, rest_samples)
    on = out[-1] + COUNT + np.arange(50) * COUNT / 5
    return _read(np.r_[out, rest, on]), 50


def test_a_rest_on_a_count_boundary_is_a_stop():
    reading, start = _strokes_with_a_rest()
    stops = find_stops(reading, [(0, reading.size)], COUNT, REVERSAL_STEPS * COUNT)
    assert len(stops) == 1
    first, last = stops[0]
    # the stop holds the rest, and may begin up to the reversal hysteresis before it
    # (a turn within it would not be read): 3 counts of 5 samples
    assert start - REVERSAL_STEPS * 5 <= first <= start
    assert start + 400 <= last <= start + 400 + 5


def test_steady_motion_has_no_stops():
    reading = _read(np.arange(2000) * COUNT / 7)
    assert find_stops(reading, [(0, reading.size)], COUNT, REVERSAL_STEPS * COUNT) == []


def test_a_pause_only_as_long_as_the_runs_beside_it_is_no_stop():
    # a rest of 8 samples between runs of 5: under STOP_RATIO times the runs beside it
    reading, _ = _strokes_with_a_rest(rest_samples=8)
    assert find_stops(reading, [(0, reading.size)], COUNT, REVERSAL_STEPS * COUNT) == []


def test_exact_positions_have_no_stops():
    reading, _ = _strokes_with_a_rest()
    assert find_stops(reading, [(0, reading.size)], 0.0, 0.0) == []


def test_no_stop_spans_two_blocks():
    reading, start = _strokes_with_a_rest()
    split = start + 200
    stops = find_stops(reading, [(0, split), (split, reading.size)], COUNT,
                       REVERSAL_STEPS * COUNT)
    assert stops and all(b <= split or a >= split for a, b in stops)


def test_the_stop_mask_is_shared_read_only():
    mask = stop_mask(10, [(2, 4), (7, 9)])
    np.testing.assert_array_equal(np.flatnonzero(mask), [2, 3, 7, 8])
    with pytest.raises(ValueError, match="read-only"):
        mask[0] = True
    assert stop_mask(10, []) is None


def test_the_bound_is_the_force_excursion_less_three_noise_stds_held_after_the_stop():
    rng = np.random.default_rng(1)
    noise = 0.01
    F = 5.0 + noise * rng.standard_normal(300)
    F[100:200] += np.linspace(0.0, 1.0, 100)  # a force that moves by 1 N in the stop
    bounds = stop_bounds(F, [(100, 200)])
    assert np.all(bounds[:100] == 0.0)
    # 1 N less 3 stds (the std estimated from the differences: within 30 %)
    assert bounds[199] == pytest.approx(1.0 - 3 * noise, abs=0.03)
    assert np.all(np.diff(bounds[100:200]) >= 0.0)  # the largest excursion so far
    assert np.all(bounds[200:] == bounds[199])


def test_a_force_that_stays_put_bounds_no_turn():
    rng = np.random.default_rng(2)
    F = 5.0 + 0.01 * rng.standard_normal(300)
    assert np.max(stop_bounds(F, [(100, 200)])) < 0.01


def test_a_count_left_back_the_way_it_came_is_a_stop_however_brief():
    # out at a count per 5 samples, a turn inside the last count (it holds 6 samples,
    # hardly longer than the runs beside it), back at a count per 5 samples: the body
    # turned there, at a time the reading does not give
    out = np.arange(50) * COUNT / 5
    turn = out[-1] + COUNT / 5 + 0.1 * COUNT * np.sin(np.linspace(0, np.pi, 6))
    back = out[::-1]
    reading = _read(np.r_[out, turn, back])
    stops = find_stops(reading, [(0, reading.size)], COUNT, REVERSAL_STEPS * COUNT)
    turned = [(a, b) for a, b in stops if a <= 52 < b]
    assert len(turned) == 1
    first, last = turned[0]
    # the run of the count the body turned in, no more: it came in at sample 48 at the
    # earliest and left 5 + 6 + 5 samples later at the latest
    assert 45 <= first <= 52 and 52 < last <= 66
    assert len(stops) == 1
