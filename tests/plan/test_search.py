"""The design search against the brute force, and its rank-one step against the
criterion computed directly."""

import numpy as np

from breakaway.plan.ramps import breakaway_measurement
from breakaway.plan.search import _gains, choose_runs, criterion, exhaustive


def _problem(draws=3, grid=18):
    rates = np.geomspace(0.02, 200, grid)
    V = np.geomspace(5.0, 80.0, draws)[:, None]
    P = {"Fc": np.full((draws, 1), 1.0), "Fs": np.full((draws, 1), 1.5), "V": V,
         "delta": np.full((draws, 1), 1.0), "s": np.ones((draws, 1)), "sigma": np.zeros((draws, 1))}
    _, _, partial = breakaway_measurement(rates, P)
    names = ["Fc", "Fs", "V", "delta"]
    rows = np.stack([partial[n] for n in names], axis=-1) / 0.01
    prior = np.broadcast_to(np.diag([1e-2, 1e-2, 1e-2, 1e-2]), (draws, 4, 4)).copy()
    return prior, rows


def test_rank_one_gain_is_the_change_of_the_criterion():
    prior, rows = _problem()
    targets = [2, 3]
    base = criterion(prior + np.einsum("qi,qj->qij", rows[:, 3], rows[:, 3]), targets)
    current = prior + np.einsum("qi,qj->qij", rows[:, 3], rows[:, 3])
    gains = _gains(current, rows, targets)
    for g in (0, 7, 17):
        added = current + np.einsum("qi,qj->qij", rows[:, g], rows[:, g])
        np.testing.assert_allclose(base + gains[g], criterion(added, targets), atol=1e-9)


def test_greedy_and_exchange_reach_the_brute_force_optimum():
    prior, rows = _problem()
    targets = [1, 2, 3]
    counts = choose_runs(prior, rows, 4, targets)
    best_counts, best, scored = exhaustive(prior, rows, 4, targets)
    assert scored == 5985  # C(18 + 4 − 1, 4)
    assert counts.sum() == 4
    found = criterion(prior + np.einsum("g,qgi,qgj->qij", counts, rows, rows), targets)
    # the search finds a design at least as good as every one of the 5985 (a tie is
    # another design of the same criterion)
    assert found <= best + 1e-6
