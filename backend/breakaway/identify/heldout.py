"""The held-out error of MODEL.md §8: fitted without some rows, scored on them."""

from __future__ import annotations

import math

import numpy as np

from .csvdata import Dataset
from .fitting import FitResult, refit

#: Evaluations of the refit on the training rows (it starts at the fit on every row).
HELDOUT_EVALUATIONS = 20


def heldout_rows(data: Dataset):
    """Training rows and held-out rows (§8: the last 20 % of a timeseries, every 5th
    row otherwise)."""
    n = data.n
    idx = np.arange(n)
    if data.kind == "timeseries":
        cut = int(round(0.8 * n))
        return idx[:cut], idx[cut:]
    test = idx[4::5]
    return np.setdiff1d(idx, test), test


def heldout_error(data: Dataset, fit: FitResult, train, test) -> float:
    """RMSE on ``test`` of ``fit``'s model refitted on ``train`` [N]."""
    trained = refit(data, fit, rows=train, max_nfev=HELDOUT_EVALUATIONS)
    r = trained.problem.measured[test] - trained.prediction[test]
    return math.sqrt(float(np.mean(r**2)))


__all__ = ["HELDOUT_EVALUATIONS", "heldout_error", "heldout_rows"]
