"""Kinematics of a measured position record that may be quantised (an encoder).

The presliding model takes x as exact and v = gradient(x, t). On an encoder record that turns
one count of jitter at rest into a reversal and a velocity spike. So:

- :func:`quantum` detects the step ``q`` of a column (0 when it takes no fixed steps);
- :func:`direction` treats a direction change smaller than ``h`` as no reversal (a
  Schmitt trigger on the running extreme); with ``h = 0`` it *is* the model's own rule;
- :func:`position_noise` estimates the noise of x, where there is any to speak of;
- v and a are taken in :mod:`.derivatives`.
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


#: The fewest decimals tried when reading the printed resolution of a column.
_MAX_DECIMALS = 12
#: A step this many printed units or more is the data's own (an encoder's count), not
#: the logger's digits, however fast the values change: rounding to the printed digits
#: leaves values on every unit, never on every second one only (a 2 µm scale or a
#: 20 µm count logged in m sits on every second unit of the finest power of ten its
#: values share).
_PRINTED_STEPS = 2
#: Gaps within this factor of the smallest are steps of one count.
_ONE_STEP = 1.5
#: Gaps up to these many steps refine the step before every gap is counted.
_REFINING_REACH = (10.0, 100.0, 1000.0)
#: One-count gaps closer than this share of a gap are the same printed value.
_SAME_GAP = 1e-3


def printed_unit(values) -> float:
    """The last printed digit's unit of a column (1e-4 for values written with 4
    decimals), or 0 when the values carry more digits than :data:`_MAX_DECIMALS`."""
    values = np.asanyarray(values, dtype=float)
    scale = max(float(np.max(np.abs(values))), 1e-300)
    for decimals in range(-6, _MAX_DECIMALS + 1):
        unit = 10.0 ** -decimals
        # a printed value parses to within a few ulps of a multiple of its unit
        if np.all(np.abs(values - unit * np.round(values / unit)) <= 1e-12 * scale):
            return unit
    return 0.0


def quantum(values, printed: float | None = None) -> float:
    """The fixed step ``q`` that every value of ``values`` sits on, or 0.

    Each gap between neighbouring distinct values is read as a whole number of steps
    (the gaps within :data:`_ONE_STEP` of the smallest are one step), the counts are
    summed, and q is the least-squares slope of the values against their counts. So a
    step that was converted and printed with few digits (encoder counts written in
    degrees with 4 decimals: gaps of q ± 1e-4) is still found.

    Parameters
    ----------
    values : array_like
        One column [any unit].
    printed : float, optional
        The unit of the last digit the column was printed with, read from the file's
        text (:attr:`~.csvdata.Dataset.printed`); else the coarsest power of ten every
        value sits on (:func:`printed_unit`), which a step of 1 µm logged in m with
        seven decimals cannot tell from digits printed to 1e-6.

    Returns
    -------
    float
        ``q`` [same unit] when at least 98 % of the distinct values lie on that grid
        (within 5 % of a step, or the printed rounding when that is coarser: the last
        printed digit, or the unit the one-count gaps show when the step was printed in
        another unit, :func:`_rounding_unit`), and q is
        either coarser than the printed digits or, when it is their unit, not negligible
        against the typical sample-to-sample change; 0 otherwise.
    """
    values = np.asanyarray(values, dtype=float)
    levels = np.unique(values)
    if levels.size < 3:
        return 0.0
    span = float(levels[-1] - levels[0])
    gaps = np.diff(levels)
    gaps = gaps[gaps > 1e-9 * span]
    if gaps.size < 2:
        return 0.0
    one_step = gaps[gaps < _ONE_STEP * gaps.min()]
    # the mean, not the median: a step printed in another unit's digits comes as two
    # gap values (3 and 4 units for a step of 3.5), and the mean is the step
    q0 = float(np.mean(one_step))
    for reach in _REFINING_REACH:
        # each gap is a whole number of steps; a gap of many steps is counted right only
        # with a step this precise, so q is refined on the short gaps first
        short = gaps[gaps < reach * q0]
        q0 = float(np.sum(short) / max(np.sum(np.round(short / q0)), 1.0))
    counts = np.concatenate([[0.0], np.cumsum(np.round(np.diff(levels) / q0))])
    q, offset = np.polyfit(counts, levels, 1)
    if not q > 0:
        return 0.0
    unit = max(printed_unit(values) if printed is None else printed, _rounding_unit(one_step))
    # printed to a unit finer than the step, each value is off the grid by its rounding
    tolerance = max(0.05 * q, 0.6 * unit) if unit < 0.5 * q else 0.05 * q
    on_grid = np.abs(levels - (offset + q * counts)) <= tolerance
    if np.mean(on_grid) < 0.98:
        return 0.0
    if q >= (_PRINTED_STEPS - 1e-6) * unit:  # (2 units, up to the float error of q)
        return float(q)  # a grid coarser than the digits: the data's own step
    # a grid of the printed digits themselves counts only where it is coarse
    changes = np.abs(np.diff(values))
    changes = changes[changes > 0]
    typical = float(np.median(changes)) if changes.size else 0.0
    return float(q) if q >= _QUANTUM_SHARE * typical else 0.0


def _rounding_unit(one_step) -> float:
    """The unit a step was rounded to when it was printed in another unit than the
    column's (encoder counts logged in degrees with four decimals, then converted to
    rad): one-count gaps then take two or more values a whole rounding unit apart
    (3 and 4 units for a count of 3.5 units). 0 when the gaps take one value."""
    values = np.sort(np.asanyarray(one_step, dtype=float))
    if values.size < 2:
        return 0.0
    jumps = np.diff(values)
    # gaps of one value differ by the conversion's float error only
    distinct = jumps[jumps > _SAME_GAP * values[-1]]
    return float(np.min(distinct)) if distinct.size else 0.0


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
    reached = 0  # the first sample at the extreme's value
    at = 0  # the last one
    for i in range(n):
        if current * (x[i] - extreme) >= 0.0:
            if x[i] != extreme:
                reached = i
            extreme = x[i]
            at = i
            d[i] = current
        elif current * (extreme - x[i]) > h:
            # a reversal at the extreme: the samples after it move the other way, and the
            # new extreme is the furthest of them in the new direction. An encoder holds
            # its extreme count for a run of samples; the turn is somewhere in that run,
            # placed in its middle (at its last sample it would be late by half the run
            # on average, and (E6') is steepest just after a turn)
            turn = (reached + at) // 2
            current = -current
            extreme = x[turn + 1]
            new_reached = new_at = turn + 1
            for j in range(turn + 1, i + 1):
                d[j] = current
                if current * (x[j] - extreme) >= 0.0:
                    if x[j] != extreme:
                        new_reached = j
                    extreme = x[j]
                    new_at = j
            reached = new_reached
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
        Hysteresis [m]; 0 gives exactly the model's own rule
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


__all__ = ["REVERSAL_STEPS", "direction", "position_noise", "printed_unit", "quantum"]
