"""What the residual says: whether it is white, and what it still depends on."""

from __future__ import annotations

import math

import numpy as np

from .noise import orderings

#: Variables with at most this many distinct values are grouped by value, not binned.
_MAX_LEVELS = 50
#: Rows per bin of a continuous variable (5 … 50 bins).
_ROWS_PER_BIN = 8


def smoothness_statistic(residual, problem) -> tuple[float, float]:
    """Low-frequency power of the residual relative to white noise, and its threshold.

    The residual (ordered along the kind's regressor) is averaged over windows of ``w``
    rows. For white noise the variance of the means is ``var/w``, so the statistic
    ``w·var(means)/var`` is 1 ± ``sqrt(2w/n)``; structure the model misses raises it.
    """
    parts = [residual[m] for m in orderings(problem)[0]]
    n = sum(p.size for p in parts)
    w = int(np.clip(n // 60, 3, 100))
    means = []
    for p in parts:
        m = p.size // w
        if m:
            means.append(p[: m * w].reshape(m, w).mean(axis=1))
    if not means:
        return 1.0, math.inf
    means = np.concatenate(means)
    var = float(np.mean(residual**2))
    stat = w * float(np.mean(means**2)) / var if var > 0 else 1.0
    threshold = 1.0 + 4.0 * math.sqrt(2.0 / max(means.size, 1)) + 0.25
    return stat, threshold


def is_white(residual, problem, noise: float, tolerance: float = 1.2) -> bool:
    """Whether the residual is indistinguishable from the measurement noise.

    Both: its RMS is within ``tolerance`` of the noise floor, and it has no more
    low-frequency power than white noise would (:func:`smoothness_statistic`).
    """
    rmse = math.sqrt(float(np.mean(residual**2)))
    stat, threshold = smoothness_statistic(residual, problem)
    return rmse <= tolerance * noise and stat <= threshold


def explained_share(residual, values) -> float:
    """Share of the residual's variance that a smooth function of ``values`` explains.

    The function is the mean of the residual in bins of ``values`` (each distinct value
    when there are few, else equal-count bins). The share white noise would reach by
    chance, ``(bins − 1)/(n − 1)``, is taken off and the rest rescaled to 0 … 1.
    """
    r = np.asanyarray(residual, dtype=float)
    values = np.asanyarray(values, dtype=float)
    n = r.size
    levels, groups = np.unique(values, return_inverse=True)
    if levels.size < 2:
        return 0.0
    if levels.size > _MAX_LEVELS:
        bins = int(np.clip(n // _ROWS_PER_BIN, 5, _MAX_LEVELS))
        rank = np.empty(n, dtype=np.int64)
        rank[np.argsort(values, kind="stable")] = np.arange(n)
        groups = rank * bins // n
    counts = np.bincount(groups)
    used = counts > 0
    centred = r - r.mean()
    total = float(np.dot(centred, centred))
    if total <= 0:
        return 0.0
    sums = np.bincount(groups, centred)
    between = float(np.sum(sums[used] ** 2 / counts[used]))
    chance = (np.count_nonzero(used) - 1) / max(n - 1, 1)
    share = (between / total - chance) / (1 - chance) if chance < 1 else 0.0
    return float(np.clip(share, 0.0, 1.0))


def correlation(a, b) -> float:
    """Pearson correlation of two arrays (0 when either is constant)."""
    a = a - a.mean()
    b = b - b.mean()
    den = math.sqrt(float(np.dot(a, a) * np.dot(b, b)))
    return float(np.dot(a, b) / den) if den > 0 else 0.0


def lag_one_correlation(residual, problem) -> float:
    """Correlation of each residual with the next along the kind's regressor (time; v;
    k within one direction and dwell): about 0 for noise, even noise whose spread
    changes; near 1 for anything the model misses that the sampling resolves (a slow
    drift as much as a 50 Hz vibration sampled at 1 kHz)."""
    r = np.asanyarray(residual, dtype=float)
    pairs = [(r[rows][:-1], r[rows][1:]) for rows in orderings(problem)[0] if rows.size > 1]
    if not pairs:
        return 0.0
    return correlation(np.concatenate([p[0] for p in pairs]),
                       np.concatenate([p[1] for p in pairs]))


def residual_structure(residual, problem, white: bool) -> list[dict]:
    """The report's ``residual_structure``: per variable of the kind, the share of the
    residual's variance a smooth function of it explains, largest first; empty when
    the residual is white."""
    if white:
        return []
    found = [{"against": name, "strength": round(explained_share(residual, values), 4)}
             for name, values in problem.variables().items()]
    return sorted(found, key=lambda item: -item["strength"])


__all__ = ["correlation", "explained_share", "is_white", "lag_one_correlation",
           "residual_structure", "smoothness_statistic"]
