"""An effect that is there holds in both halves of a time series; only what a half
determines votes."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify.stability import multiple_correlation


def test_a_parameter_that_the_others_make_together_has_a_high_multiple_correlation():
    # x0 = x1 + x2 with independent x1, x2: each pair correlates at 0.71, yet x0 is
    # wholly what the other two make
    rng = np.random.default_rng(0)
    x1, x2 = rng.standard_normal((2, 20000))
    x3 = rng.standard_normal(20000)
    R = np.corrcoef([x1 + x2 + 0.05 * x3, x1, x2])
    assert np.max(np.abs(R[0, 1:])) < 0.72
    assert multiple_correlation(R, 0) > 0.99
    # an independent parameter: none
    R = np.corrcoef([x3, x1, x2])
    assert multiple_correlation(R, 0) < 0.05
    # a flat direction: the pair is one
    assert multiple_correlation(np.array([[1.0, 1.0], [1.0, 1.0]]), 0) == pytest.approx(1.0)
    assert multiple_correlation(np.array([[1.0]]), 0) == 0.0
