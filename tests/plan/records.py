"""Seeded first records and their reports, the starting points of the plans tested
here (made by code, never pasted)."""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from breakaway.identify import identify
from breakaway.identify.synthetic import _dataset, make_dataset
from breakaway.quasistatic import breakaway_force
from breakaway.steady import steady_state_force

#: The note's Fig. 5 curve with V = 50 (s = 1, normalised units).
RAMP_TRUTH = {"Fc": 1.0, "Fs": 1.5, "V": 50.0, "delta": 1.0}
#: A steady curve of a small actuator (N, m/s).
STEADY_TRUTH = {"Fc": 10.0, "Fs": 15.0, "V": 0.005, "delta": 1.0}


def ramps_record(seed: int, low: float, high: float, noise: float, truth=RAMP_TRUTH):
    """Break-away forces at 8 rates from ``low`` to ``high`` [N/s], three runs each."""
    rng = np.random.default_rng(seed)
    k = np.repeat(np.geomspace(low, high, 8), 3)
    F = breakaway_force(k, **truth) + noise * rng.standard_normal(k.size)
    return _dataset("breakaway", {"k": k, "F_ba": F}, {"s": "1.0"})


def steady_record(seed: int, slowest: float, noise: float, rows: int = 40, truth=STEADY_TRUTH):
    """A steady curve at ``rows`` speeds per direction from ``slowest`` to 0.05 m/s."""
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(slowest, 0.05, rows)
    v = np.concatenate([-speeds[::-1], speeds])
    F = steady_state_force(v, **truth) + noise * rng.standard_normal(v.size)
    return _dataset("steady", {"v": v, "F": F})


@lru_cache(maxsize=None)
def high_rates(seed: int = 1):
    """Ramps only at high rates (40 to 300 N/s: break-away speeds far above V): V and δ
    wholly open, Fs beyond the data. (record, report)"""
    record = ramps_record(seed, 40.0, 300.0, 0.005)
    return record, identify(record)


@lru_cache(maxsize=None)
def timeseries(seed: int = 0):
    """A short synthetic time series (every parameter determined). (record, report)"""
    record, _ = make_dataset("timeseries", seed=seed, n=3000, noise=0.3)
    return record, identify(record)


@lru_cache(maxsize=None)
def steady(seed: int = 0):
    """A steady curve from the slowest speed V on. (record, report)"""
    record = steady_record(seed, STEADY_TRUTH["V"], 0.05)
    return record, identify(record)
