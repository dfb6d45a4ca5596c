"""Kinematics of a measured position record that may be quantised (an encoder).

MODEL.md §3 takes x as exact and v = gradient(x, t). On an encoder record that turns
one count of jitter at rest into a reversal and a velocity spike. So:

- :func:`quantum` detects the step ``q`` of a column (0 when it takes no fixed steps);
- :func:`direction` treats a direction change smaller than ``h`` as no reversal (a
  Schmitt trigger on the running extreme); with ``h = 0`` it *is* MODEL.md §3's rule;
- :func:`velocity` differentiates x after a moving average just long enough that a
  typical stroke covers several counts (plain ``gradient`` when ``q = 0``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.ndimage import uniform_filter1d

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


def velocity(t, x, q: float = 0.0):
    """Velocity of a position record [m/s].

    ``gradient(x, t)`` (MODEL.md §3) when ``q = 0``. For a quantised record, x is first
    averaged over a centred window long enough that a typical stroke moves about
    four counts in it (5 … 201 samples), so one count is not a spike.
    """
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    if q <= 0 or x.size < 5:
        return np.gradient(x, t)
    return np.gradient(uniform_filter1d(x, smoothing_window(t, x, q), mode="nearest"), t)


def smoothing_window(t, x, q: float) -> int:
    """Odd window [samples] over which a typical stroke moves about four counts ``q``."""
    dt = float(np.median(np.diff(t)))
    lag = min(25, x.size - 1)
    speed = float(np.percentile(np.abs(x[lag:] - x[:-lag]), 90)) / (lag * dt)
    if not speed > 0:
        return 5
    half = math.ceil(2.0 * q / (speed * dt))
    return int(np.clip(2 * half + 1, 5, min(201, x.size - (x.size + 1) % 2)))


__all__ = ["REVERSAL_STEPS", "direction", "quantum", "smoothing_window", "velocity"]
