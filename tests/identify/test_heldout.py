"""The held-out error on blocks of the record: the blocks, and refits without a block
by chord steps that agree with full refits."""

from __future__ import annotations

import math

import numpy as np
import pytest

from breakaway.identify.fitting import fit_model, refit
from breakaway.identify.heldout import BLOCKS, HeldOut, heldout_blocks, heldout_error
from breakaway.identify.models import problem_for
from breakaway.identify.synthetic import _dataset, make_dataset


def _strokes(count, rows=6000):
    """``count`` strokes of different lengths over ``rows`` samples."""
    rng = np.random.default_rng(count)
    t = np.linspace(0.0, 60.0, rows)
    turns = np.sort(rng.uniform(0.0, 60.0, count - 1))
    phase = np.interp(t, np.concatenate([[0.0], turns, [60.0]]), np.arange(count + 1))
    x = 0.01 * np.abs((phase % 2.0) - 1.0)
    return _dataset("timeseries", {"t": t, "x": x, "F": np.sign(np.gradient(x))})


def test_a_time_series_is_cut_into_whole_strokes():
    data = _strokes(60)
    problem = problem_for(data)
    blocks = heldout_blocks(problem)
    assert len(blocks) == BLOCKS
    assert np.array_equal(np.concatenate(blocks), np.arange(data.n))
    starts = set(np.flatnonzero(np.diff(problem.d) != 0) + 1)
    # every cut is at a reversal, and the blocks are of similar size
    assert all(int(b[0]) in starts for b in blocks[1:])
    sizes = np.array([b.size for b in blocks])
    assert sizes.max() < 2 * sizes.min()


def test_a_record_of_few_strokes_is_cut_in_time():
    data = _strokes(6)
    blocks = heldout_blocks(problem_for(data))
    assert [b.size for b in blocks] == [data.n // BLOCKS] * BLOCKS


@pytest.mark.parametrize("kind", ["steady", "breakaway"])
def test_separate_measurements_are_dealt_to_the_blocks_in_turn(kind):
    data, _ = make_dataset(kind, seed=1)
    problem = problem_for(data)
    blocks = heldout_blocks(problem)
    assert len(blocks) >= 5
    assert np.array_equal(np.sort(np.concatenate(blocks)), np.arange(data.n))
    speed = problem.regressor_speed()
    # each block spans the whole range of the regressor
    for block in blocks:
        assert speed[block].min() <= np.percentile(speed, 15)
        assert speed[block].max() >= np.percentile(speed, 85)


@pytest.mark.parametrize("kind", ["steady", "breakaway", "timeseries"])
def test_chord_refits_match_full_refits_without_each_block(kind):
    data, _ = make_dataset(kind, seed=2, n=3000)
    fit = fit_model(data)
    blocks = heldout_blocks(fit.problem)
    chord = heldout_error(fit, blocks)
    full = []
    for block in blocks:
        keep = np.setdiff1d(np.arange(data.n), block)
        trained = refit(data, fit, rows=keep)
        r = trained.problem.measured[block] - trained.prediction[block]
        full.append(float(np.dot(r, r)))
    assert chord.sse() == pytest.approx(np.array(full), rel=0.05)
    assert chord.rmse == pytest.approx(math.sqrt(sum(full) / data.n), rel=0.02)
    # predicting rows it did not see, the model does worse than on rows it did
    assert chord.rmse > fit.rmse


def test_the_weighted_heldout_error_counts_each_row_by_its_weight():
    # rows where x's reading makes the force uncertain (weight 1/100) hardly count
    residual = np.r_[np.full(90, 0.1), np.full(10, 3.0)]
    held = HeldOut(residual, [np.arange(100)])
    weights = np.r_[np.ones(90), np.full(10, 0.01)]
    expected = math.sqrt((90 * 0.01 + 10 * 0.01 * 9.0) / (90 + 0.1))
    assert held.weighted_rmse(weights) == pytest.approx(expected, rel=1e-12)
    assert held.weighted_rmse(None) == pytest.approx(held.rmse, rel=1e-12)
    assert held.rmse == pytest.approx(math.sqrt((90 * 0.01 + 10 * 9.0) / 100), rel=1e-12)
