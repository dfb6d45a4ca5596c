"""Starting points read off the data (``starts.py``)."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify.models import problem_for
from breakaway.identify.starts import (FASTEST_SHARES, SPEED_FACTOR, TYPICAL_SHARES,
                                       _stribeck_speeds, base_starts)
from breakaway.identify.synthetic import _dataset


def _steady(speeds, seed=0):
    rng = np.random.default_rng(seed)
    v = np.r_[speeds, -speeds]
    F = np.sign(v) * (1.0 + 0.01 * rng.standard_normal(v.size))
    return problem_for(_dataset("steady", {"v": v, "F": F}), (), {}, None)


def test_stribeck_speeds_reach_the_fastest_when_it_lies_far_beyond_the_typical():
    # creeps at 10–30 µm/s in 96 % of the rows, slips at 5–15 mm/s in 4 %: the 95th
    # percentile is a creep's, and the drop where slips start lies far above it
    rng = np.random.default_rng(1)
    speeds = np.r_[rng.uniform(1e-5, 3e-5, 960), rng.uniform(5e-3, 1.5e-2, 40)]
    problem = _steady(speeds)
    typical, fastest = problem.scales.speed, float(np.max(np.abs(problem.v)))
    assert typical < 3.1e-5 and fastest > 1e-2
    V = _stribeck_speeds(problem)
    assert V[:len(TYPICAL_SHARES)] == pytest.approx([typical * s for s in TYPICAL_SHARES])
    assert V[len(TYPICAL_SHARES):] == pytest.approx([fastest * s for s in FASTEST_SHARES])
    # every start is tried with each of them
    assert sorted({s["V"] for s in base_starts(problem)}) == pytest.approx(sorted(V))


def test_stribeck_speeds_add_nothing_where_the_fastest_is_typical():
    # a sweep of set-points: the fastest is within a factor 2 of the 95th percentile,
    # and its shares lie beside the typical speed's
    problem = _steady(np.geomspace(1e-3, 1e-1, 40))
    V = _stribeck_speeds(problem)
    assert len(V) == len(TYPICAL_SHARES)
    ratios = np.array(V)[1:] / np.array(V)[:-1]
    assert np.all(ratios >= SPEED_FACTOR)
