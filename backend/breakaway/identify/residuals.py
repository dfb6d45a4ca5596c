"""What the residual says: a model-free noise floor, whiteness, and the signature of
each §7 effect (the evidence the diagnosis reports)."""

from __future__ import annotations

import math
from math import comb

import numpy as np

from .models import Problem

_MAD_TO_STD = 1.4826


def _replicate_sigma(F, keys):
    """Pooled within-group std of rows sharing ``keys`` (NaN with too few replicates)."""
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    replicated = counts[inverse] >= 2
    if replicated.sum() < max(6, 0.3 * F.size):
        return math.nan
    means = np.bincount(inverse, F) / counts
    dev = F[replicated] - means[inverse[replicated]]
    dof = replicated.sum() - np.count_nonzero(counts >= 2)
    return float(math.sqrt(np.dot(dev, dev) / max(dof, 1)))


def _groupings(problem: Problem):
    """Ways to split the rows into groups ordered by the regressor, inside which F varies
    smoothly; the first is the finest."""
    kind = problem.data.kind
    if kind == "timeseries":
        return [[np.arange(problem.data.n)]]
    if kind == "steady":
        order = np.argsort(problem.v, kind="stable")
        v = problem.v[order]
        return [[order[v < 0], order[v > 0]]]
    keys = np.column_stack([problem.direction, problem.dwell])
    order = np.lexsort((problem.k, problem.dwell, problem.direction))
    fine = [order[np.all(keys[order] == key, axis=1)] for key in np.unique(keys, axis=0)]
    # dwell may not matter: then rows at one rate are replicates along k per direction
    order = np.lexsort((problem.k, problem.direction))
    coarse = [order[problem.direction[order] == value] for value in np.unique(problem.direction)]
    return [fine, coarse]


def noise_floor(problem: Problem) -> float:
    """Model-free estimate of the measurement noise std [N].

    Each estimate below is unbiased when its assumption holds and too high otherwise, so
    the smallest is taken. Rows with the same regressor (replicates) give the noise
    directly (pooled within groups). Otherwise F is taken as smooth along time
    (``timeseries``) or along the regressor (``steady``: v, ``breakaway``: k, per direction and dwell, or per
    direction only): robust (MAD) estimates from second and third differences.
    """
    F = problem.measured
    kind = problem.data.kind
    estimates = []
    if kind == "steady":
        estimates.append(_replicate_sigma(F, problem.v[:, None]))
    elif kind == "breakaway":
        estimates.append(_replicate_sigma(F, np.column_stack(
            [problem.k, problem.direction, problem.dwell])))
        # if dwell does not matter, rows at one rate and direction are replicates too
        estimates.append(_replicate_sigma(F, np.column_stack([problem.k, problem.direction])))
    for groups in _groupings(problem):
        for order in (2, 3):
            diffs = [np.diff(F[g], order) / math.sqrt(comb(2 * order, order))
                     for g in groups if g.size > order + 2]
            if diffs:
                e = np.concatenate(diffs)
                estimates.append(_MAD_TO_STD * float(np.median(np.abs(e))))
    estimates = [e for e in estimates if math.isfinite(e)]
    floor = min(estimates) if estimates else math.nan
    if not floor > 0:
        # quantised, noiseless data: the quantisation step's uniform noise
        steps = np.diff(np.unique(F))
        floor = float(np.min(steps)) / math.sqrt(12) if steps.size else 0.0
    return floor


def smoothness_statistic(residual, problem: Problem) -> tuple[float, float]:
    """Low-frequency power of the residual relative to white noise, and its threshold.

    The residual (ordered as in :func:`noise_floor`) is averaged over windows of ``w``
    rows. For white noise the variance of the means is ``var/w``, so the statistic
    ``w·var(means)/var`` is 1 ± ``sqrt(2w/n)``; structure the model misses raises it.
    """
    parts = [residual[m] for m in _groupings(problem)[0]]
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


def is_white(residual, problem: Problem, noise: float, tolerance: float = 1.2) -> bool:
    """Whether the residual is indistinguishable from the measurement noise.

    Both: its RMS is within ``tolerance`` of the noise floor, and it has no more
    low-frequency power than white noise would (:func:`smoothness_statistic`).
    """
    rmse = math.sqrt(float(np.mean(residual**2)))
    stat, threshold = smoothness_statistic(residual, problem)
    return rmse <= tolerance * noise and stat <= threshold


# ---------------------------------------------------------------------------------
# signatures: one number and one sentence per effect
# ---------------------------------------------------------------------------------


def _corr(a, b):
    a = a - a.mean()
    b = b - b.mean()
    den = math.sqrt(float(np.dot(a, a) * np.dot(b, b)))
    return float(np.dot(a, b) / den) if den > 0 else 0.0


def _fmt(value):
    return f"{value:.3g}"


def signature(effect: str, problem: Problem, residual: np.ndarray, params: dict) -> str:
    """One sentence on what in ``residual`` points to ``effect``."""
    kind = problem.data.kind
    r = residual
    if kind == "timeseries":
        v, d = problem.v, problem.d
        sliding = np.abs(v) >= np.median(np.abs(v))
    elif kind == "steady":
        v, d, sliding = problem.v, np.sign(problem.v), np.ones(r.size, dtype=bool)
    else:
        v = problem.k
        d = problem.direction
        sliding = np.ones(r.size, dtype=bool)
    if effect == "viscous":
        c = _corr(r[sliding] * d[sliding], np.abs(v[sliding]))
        what = "k" if kind == "breakaway" else "|v| in sliding"
        return f"the residual grows with {what} in the direction of motion (r = {c:.2f})"
    if effect in ("asymmetry", "offset"):
        pos = r[sliding & (d > 0)]
        neg = r[sliding & (d < 0)]
        mp = float(np.mean(pos)) if pos.size else 0.0
        mn = float(np.mean(neg)) if neg.size else 0.0
        if effect == "offset":
            return (f"the residual has the same sign in both directions: mean {_fmt(mp)} N "
                    f"moving positive, {_fmt(mn)} N moving negative")
        if kind == "breakaway":
            return (f"the break-away force differs by direction: residual {_fmt(mp)} N for "
                    f"direction +1 and {_fmt(mn)} N for direction -1")
        return (f"the sliding levels differ by direction: measured |F| minus the model's "
                f"is {mp:+.3g} N moving positive and {-mn:+.3g} N moving negative")
    if effect == "drift":
        c = _corr(r[sliding] * d[sliding], problem.t[sliding])
        return f"the sliding-level error changes steadily with time (r = {c:.2f} against t)"
    if effect == "inertia":
        if kind == "breakaway":
            c = _corr(r, problem.k**2)
            return f"the residual grows with k² like an inertial term (r = {c:.2f})"
        c = _corr(r, problem.a)
        return f"the residual follows the acceleration a = dv/dt (r = {c:.2f})"
    if effect == "ripple":
        lam = params.get("wavelength")
        if lam is None:
            return "the residual is periodic in x"
        phase = 2 * np.pi * problem.x / lam
        c = math.hypot(_corr(r, np.sin(phase)), _corr(r, np.cos(phase)))
        return (f"the residual is periodic in x with wavelength {_fmt(lam)} m "
                f"(correlation {c:.2f} with a sinusoid of x)")
    if effect == "lag":
        c = _corr(r[sliding] * d[sliding], problem.a[sliding] * d[sliding])
        return (f"in sliding the error depends on whether the speed rises or falls "
                f"(r = {c:.2f} against the acceleration along the motion): F–v loops open")
    if effect == "backlash":
        after = _after_reversal(problem, params)
        if after.any() and (~after).any():
            inside = math.sqrt(float(np.mean(r[after] ** 2)))
            outside = math.sqrt(float(np.mean(r[~after] ** 2)))
            return (f"the residual concentrates right after reversals: RMS {_fmt(inside)} N "
                    f"in the first part of each new stroke against {_fmt(outside)} N elsewhere")
        return "the residual concentrates right after reversals"
    if effect == "dwell":
        c = _corr(r, np.log1p(problem.dwell))
        return f"the break-away force rises with the dwell time (r = {c:.2f} against ln(1 + dwell))"
    raise ValueError(f"unknown effect {effect!r}")


def _after_reversal(problem: Problem, params: dict):
    """Rows within two presliding distances (or the fitted play) of the last reversal."""
    x, d = problem.x, problem.d
    reversal = np.flatnonzero(np.diff(d) != 0) + 1
    start = np.zeros(x.size, dtype=int)
    start[reversal] = reversal
    start = np.maximum.accumulate(start)
    travel = np.abs(x - x[np.maximum(start - 1, 0)])
    reach = max(2.0 / params.get("s", math.inf), params.get("play", 0.0) * 1.5)
    return (travel <= reach) & (start > 0)
