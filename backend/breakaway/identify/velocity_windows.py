"""Each sample's velocity window over a position record, compiled.

The kernels of :func:`.derivatives.velocity`: a sample's window is the narrowest centred
one over which x spans a given range, widened a sample a side while x stays on its
line (an encoder's steady speed timed over its whole straight run), and v is the
least-squares slope over it. :func:`_velocity_at` takes v at chosen samples only and
says how far each one's window read (its reach), so that a record changed elsewhere
keeps the v it had.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .local_fits import _take_window


@njit(cache=True)
def _adaptive_velocity(t, x, span, max_half, with_spread, error, tolerance):
    n = x.size
    v = np.empty(n)
    duration = np.empty(n)
    spread = np.zeros(n if with_spread else 0)
    for i in range(n):
        lo, hi, slope = _window(t, x, i, span, max_half, tolerance)
        _take_window(t, x, i, lo, hi, v, duration, spread, with_spread, error, slope)
    return v, duration, spread


@njit(cache=True)
def _velocity_at(t, x, span, max_half, tolerance, rows, v, reach):
    """``v`` [m/s] at ``rows`` taken as :func:`_adaptive_velocity` takes it, and each
    such row's ``reach``: the first and last sample its window read (one more a side
    than the window: the narrowest window's search and the widening stop there)."""
    n = x.size
    duration = np.empty(n)
    spread = np.zeros(0)
    for i in rows:
        lo, hi, slope = _window(t, x, i, span, max_half, tolerance)
        _take_window(t, x, i, lo, hi, v, duration, spread, False, 0.0, slope)
        reach[i, 0] = max(lo - 1, 0)
        reach[i, 1] = min(hi + 1, n - 1)


@njit(cache=True)
def _window(t, x, i, span, max_half, tolerance):
    """Sample ``i``'s window [lo, hi]: the narrowest centred one over which x spans
    ``span`` (at most ``max_half`` samples a side), widened (``tolerance`` > 0) while x
    stays on its line (:func:`_widened`), and x's slope over it where the widening
    found it (NaN otherwise)."""
    n = x.size
    w = 1
    low = high = x[i]
    while True:
        lo = max(i - w, 0)
        hi = min(i + w, n - 1)
        # the range the window covers, not its ends' difference: at a turn the two
        # ends sit at the same height while the body has moved
        low = min(low, x[lo], x[hi])
        high = max(high, x[lo], x[hi])
        if high - low >= span or w >= max_half or (lo == 0 and hi == n - 1):
            break
        w += 1
    if high - low >= span and tolerance > 0.0:
        return _widened(t, x, i, lo, hi, max_half, tolerance)
    return lo, hi, np.nan


@njit(cache=True)
def _widened(t, x, i, lo, hi, max_half, tolerance):
    """The window [lo, hi] about sample ``i`` widened a sample a side at a time while
    both new ends lie within ``tolerance`` [m] of the least-squares line through the
    widened window (at most ``max_half`` samples a side), and x's slope over it."""
    n = x.size
    count = st = sx = stt = stx = 0.0
    for j in range(lo, hi + 1):
        count, st, sx, stt, stx = _with_sample(t, x, i, j, count, st, sx, stt, stx)
    while hi - i < max_half and i - lo < max_half and (lo > 0 or hi < n - 1):
        new_lo, new_hi = max(lo - 1, 0), min(hi + 1, n - 1)
        c, a, b, aa, ab = count, st, sx, stt, stx
        for j in (new_lo, new_hi):
            if j < lo or j > hi:
                c, a, b, aa, ab = _with_sample(t, x, i, j, c, a, b, aa, ab)
        # an end's departure from the line times c·D, where D = c·Σt² − (Σt)² and the
        # line's slope is (c·Σtx − Σt·Σx)/D: the test without a division per step
        spread_t = c * aa - a * a
        if spread_t <= 0.0:
            break
        rise = c * ab - a * b
        departure = max(_scaled_departure(t, x, i, new_lo, c, a, b, spread_t, rise),
                        _scaled_departure(t, x, i, new_hi, c, a, b, spread_t, rise))
        if departure > tolerance * c * spread_t:
            break
        count, st, sx, stt, stx = c, a, b, aa, ab
        lo, hi = new_lo, new_hi
    spread_t = count * stt - st * st
    return lo, hi, (count * stx - st * sx) / spread_t if spread_t > 0.0 else np.nan


@njit(cache=True)
def _scaled_departure(t, x, i, j, count, st, sx, spread_t, rise):
    """|x_j − the line of the window's sums| times ``count``·``spread_t``."""
    return abs((count * (x[j] - x[i]) - sx) * spread_t - rise * (count * (t[j] - t[i]) - st))


@njit(cache=True)
def _with_sample(t, x, i, j, count, st, sx, stt, stx):
    """The sums of a line's fit about sample ``i`` with sample ``j`` added."""
    dt, dx = t[j] - t[i], x[j] - x[i]
    return count + 1.0, st + dt, sx + dx, stt + dt * dt, stx + dt * dx
