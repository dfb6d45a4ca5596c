"""Kinematics of a measured position record that may be quantised (an encoder).

MODEL.md §3 takes x as exact and v = gradient(x, t). On an encoder record that turns
one count of jitter at rest into a reversal and a velocity spike. So:

- :func:`quantum` detects the step ``q`` of a column (0 when it takes no fixed steps);
- :func:`direction` treats a direction change smaller than ``h`` as no reversal (a
  Schmitt trigger on the running extreme); with ``h = 0`` it *is* MODEL.md §3's rule;
- :func:`position_noise` estimates the noise of x, where there is any to speak of;
- :func:`velocity` takes each sample's slope over a window just wide enough that x
  moves several resolutions in it (plain ``gradient`` when x is exact).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..presliding import motion_direction

#: Direction changes smaller than this many quantisation steps are not reversals.
REVERSAL_STEPS = 3
#: A column counts as quantised when its step is at least this share of the typical
#: change between neighbouring samples (a float's storage resolution is far smaller).
_QUANTUM_SHARE = 0.05


def quantum(values) -> float:
    """The fixed step ``q`` that every value of ``values`` sits on, or 0.

    Parameters
    ----------
    values : array_like
        One column [any unit].

    Returns
    -------
    float
        ``q`` [same unit] when at least 98 % of the distinct values are integer
        multiples of the smallest gap between distinct values (within 5 % of a step)
        and that gap is not negligible against the typical sample-to-sample change;
        0 otherwise.
    """
    values = np.asanyarray(values, dtype=float)
    levels = np.unique(values)
    if levels.size < 3:
        return 0.0
    span = float(levels[-1] - levels[0])
    gaps = np.diff(levels)
    gaps = gaps[gaps > 1e-9 * span]
    if gaps.size == 0:
        return 0.0
    q = float(gaps.min())
    ratio = (levels - levels[0]) / q
    on_grid = np.abs(ratio - np.round(ratio)) < 0.05
    if np.mean(on_grid) < 0.98:
        return 0.0
    changes = np.abs(np.diff(values))
    changes = changes[changes > 0]
    typical = float(np.median(changes)) if changes.size else 0.0
    return q if q >= _QUANTUM_SHARE * typical else 0.0


@njit(cache=True)
def _direction_kernel(x, h):
    n = x.size
    d = np.ones(n)
    start = -1
    for i in range(1, n):
        if abs(x[i] - x[0]) > h:
            start = i
            break
    if start < 0:
        return d
    current = 1.0 if x[start] > x[0] else -1.0
    extreme = x[0]
    at = 0
    for i in range(n):
        if current * (x[i] - extreme) >= 0.0:
            extreme = x[i]
            at = i
            d[i] = current
        elif current * (extreme - x[i]) > h:
            # a reversal at the extreme: the samples after it move the other way, and the
            # new extreme is the furthest of them in the new direction
            current = -current
            extreme = x[at + 1]
            new_at = at + 1
            for j in range(at + 1, i + 1):
                d[j] = current
                if current * (x[j] - extreme) >= 0.0:
                    extreme = x[j]
                    new_at = j
            at = new_at
        else:
            d[i] = current
    return d


def direction(x, h: float = 0.0):
    """Direction ``d_i`` of each sample, ignoring direction changes of ``h`` or less.

    Parameters
    ----------
    x : array_like
        Positions [m].
    h : float, optional
        Hysteresis [m]; 0 gives exactly MODEL.md §3's rule
        (:func:`breakaway.presliding.motion_direction`).

    Returns
    -------
    numpy.ndarray
        ±1 per sample. A reversal is placed at the running extreme, so (E6') takes
        ``x_r`` there.
    """
    x = np.ascontiguousarray(x, dtype=float)
    if h <= 0:
        return motion_direction(x)
    return _direction_kernel(x, float(h))


def position_noise(x) -> float:
    """Noise std of a position record [m], or 0 where it is negligible.

    Robust (MAD) third differences (``std = σ·√20`` for white noise). Counted only when
    it is at least 5 % of the typical sample-to-sample change: the curvature of a clean,
    finely sampled record gives a far smaller value.
    """
    x = np.asanyarray(x, dtype=float)
    if x.size < 8:
        return 0.0
    sigma = 1.4826 * float(np.median(np.abs(np.diff(x, 3)))) / math.sqrt(20)
    changes = np.abs(np.diff(x))
    changes = changes[changes > 0]
    typical = float(np.median(changes)) if changes.size else 0.0
    return sigma if sigma >= _QUANTUM_SHARE * typical and sigma > 0 else 0.0


#: An adaptive window spans at least this many resolutions of x ...
WINDOW_RESOLUTIONS = 8
#: ... and at most this many samples on each side.
MAX_HALF_WINDOW = 100


@njit(cache=True)
def _adaptive_velocity(t, x, span, max_half):
    n = x.size
    v = np.empty(n)
    for i in range(n):
        w = 1
        while True:
            lo = max(i - w, 0)
            hi = min(i + w, n - 1)
            if abs(x[hi] - x[lo]) >= span or w >= max_half or (lo == 0 and hi == n - 1):
                break
            w += 1
        # least-squares slope over the window: the counts' ±q/2 errors average out
        # where an end-to-end difference would keep two of them
        tm = 0.0
        xm = 0.0
        for j in range(lo, hi + 1):
            tm += t[j]
            xm += x[j]
        tm /= hi - lo + 1
        xm /= hi - lo + 1
        num = 0.0
        den = 0.0
        for j in range(lo, hi + 1):
            num += (t[j] - tm) * (x[j] - xm)
            den += (t[j] - tm) ** 2
        v[i] = num / den
    return v


def velocity(t, x, resolution: float = 0.0):
    """Velocity of a position record [m/s].

    ``gradient(x, t)`` (MODEL.md §3) when x is exact (``resolution = 0``). For an
    encoder's steps or a noisy x, each sample's velocity is the slope over the
    narrowest centred window in which x moves by at least
    :data:`WINDOW_RESOLUTIONS` resolutions (at most :data:`MAX_HALF_WINDOW` samples on
    each side): fast motion keeps its detail, slow motion is timed over several counts
    instead of showing one count as a spike, and jitter at rest averages out.
    """
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    if x.size < 5 or resolution <= 0:
        return np.gradient(x, t)
    return _adaptive_velocity(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW)


__all__ = ["REVERSAL_STEPS", "direction", "position_noise", "quantum", "velocity"]
