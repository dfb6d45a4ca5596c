"""Strokes of a time series: where each began, and where each direction breaks away.

Pure functions of the record's direction d, its positions x and the presliding fraction
z = s·|x − x_r| a fit gives each row; the problem
(:class:`.models.timeseries.TimeseriesProblem`) calls them with its own.
"""

from __future__ import annotations

import numpy as np

#: Each direction breaks away at one place when its break-aways lie within this share
#: of the distance between the two directions' (:func:`breakaways_apart`).
ONE_PLACE_SHARE = 0.25


def last_reversal(d) -> tuple[np.ndarray, np.ndarray]:
    """Index of the sample before each row's last reversal (0 before the first), and
    whether the row has one.

    Parameters
    ----------
    d : array_like
        Direction of motion of each row (±1; a reversal is where it changes).
    """
    d = np.asanyarray(d)
    change = np.flatnonzero(np.diff(d) != 0) + 1
    start = np.zeros(d.size, dtype=int)
    start[change] = change
    start = np.maximum.accumulate(start)
    return np.maximum(start - 1, 0), start > 0


def breakaway_places(x, d, z, sliding_z) -> tuple[np.ndarray, np.ndarray]:
    """x [m] at each reversal that starts a stroke reaching gross sliding, for the
    strokes moving positive and those moving negative: where each direction breaks
    away.

    Parameters
    ----------
    x : array_like
        Position of each row [m].
    d : array_like
        Direction of motion of each row (±1).
    z : array_like
        Presliding fraction s·|x − x_r| of each row [-].
    sliding_z : float
        The fraction from which a row is in gross sliding [-].
    """
    x, d, z = np.asanyarray(x), np.asanyarray(d), np.asanyarray(z)
    last, reversed_ = last_reversal(d)
    sliding = reversed_ & (z >= sliding_z)
    starts, rows = np.unique(last[sliding], return_index=True)
    ways = d[np.flatnonzero(sliding)[rows]]
    return x[starts[ways > 0]], x[starts[ways < 0]]


def breakaways_apart(positive, negative) -> bool:
    """Whether each direction breaks away at one place of its own: all its break-aways
    (``positive`` and ``negative`` places [m], :func:`breakaway_places`) within
    :data:`ONE_PLACE_SHARE` of the distance between the two directions' median places.

    A rig that turns only at the two ends of its travel breaks away one way at one end
    and the other way at the other, and a stiction that depends on position predicts
    the same as one that depends on direction; break-aways spread along the travel each
    way would show such a dependence within a direction. A direction that never breaks
    away tells the two apart no better.
    """
    positive, negative = np.asanyarray(positive), np.asanyarray(negative)
    if positive.size == 0 or negative.size == 0:
        return True
    distance = abs(float(np.median(positive)) - float(np.median(negative)))
    return max(float(np.ptp(positive)), float(np.ptp(negative))) \
        < ONE_PLACE_SHARE * distance
