"""Isolated spikes in the measured force: found, set aside, and said.

A spike (a glitch of the force sensor or its wiring) is one row far from its neighbours.
Friction does not do that: every effect of the library, and every effect outside it that
a report should trace, moves the force smoothly along the kind's regressor (time, v, or
k within one direction and dwell), with steps and corners at most (a reversal). So a row
is a spike when its residual lies more than :data:`SPIKE_SIGMAS` robust standard
deviations (taken over the rows around it) from the median of the rows before it and,
on the same side, from the median of the rows after it (a step or a corner agrees with
one side; a ramp lies above one and below the other), while the rows next to it are
ordinary (a peak some rows wide is a feature, not a glitch). Medians are not pulled by
a spike among the rows they take. In a time series the measured force must stand out
too: a residual spike under a smooth force is the model's (a glitch of x or t). Left
in, a few spikes inflate the RMSE, the BIC and the residual's low-frequency power, and
the report would say that structure is left where there is none.

A time series keeps every row (the presliding state runs along x); a spike's F is
replaced by the median of its neighbours' F. Rows of a steady or break-away file are
separate measurements, so a spike's row is left out.
"""

from __future__ import annotations

import numpy as np
from scipy.ndimage import median_filter

from .noise import orderings

#: Rows on either side of a row that its residual is compared with.
HALF_WINDOW = 3
#: Rows on either side over which the residual's spread is taken: local, so that noise
#: that grows with speed (or anything else) is not taken for spikes where it is large.
SCALE_HALF_WINDOW = 100
#: A spike lies further than this many robust standard deviations from its neighbours:
#: Gaussian noise does so once in 5·10⁸ rows.
SPIKE_SIGMAS = 6.0
#: ... and the rows next to it lie within this many: a peak some rows wide (a fast
#: feature of the friction itself, a break-away at motion onset) is not a spike.
NEIGHBOUR_SIGMAS = 3.0
#: Spikes are rare; more rows than this share (and more than one) are heavy-tailed
#: noise, not spikes.
MAX_SHARE = 0.02
#: From median absolute deviation to standard deviation (Gaussian).
_MAD_TO_STD = 1.4826


def running_median(values, half_window: int = HALF_WINDOW, neighbours_only: bool = False):
    """Median of each value and its ``half_window`` neighbours on either side (fewer at
    the ends; NaN values are not counted), or of the neighbours alone.

    Parameters
    ----------
    values : array_like, shape (n,)
    half_window : int
    neighbours_only : bool
        Leave each value out of its own median (a spike is then measured against what
        surrounds it, and white noise's deviation keeps its full spread).

    Returns
    -------
    numpy.ndarray, shape (n,)
    """
    values = np.asanyarray(values, dtype=float)
    padded = np.pad(values, half_window, mode="constant", constant_values=np.nan)
    windows = np.lib.stride_tricks.sliding_window_view(padded, 2 * half_window + 1)
    if neighbours_only:
        windows = np.delete(windows, half_window, axis=1)
    return _row_medians(windows)


def _row_medians(windows) -> np.ndarray:
    """Median of each row of ``windows``, NaN not counted. ``numpy.nanmedian`` takes a
    slow path for rows of a few values (the spike search on a million rows: 2.5 s with
    it everywhere, 0.6 s so); only the rows that hold a NaN (a record's ends, a
    set-aside spike), whose plain median is NaN, need it."""
    medians = np.median(windows, axis=1)
    gaps = np.isnan(medians)
    if gaps.any():
        medians[gaps] = np.nanmedian(windows[gaps], axis=1)
    return medians


def _stands_out(values, unit, sigmas: float):
    """Where each value lies more than ``sigmas`` ``unit`` from the median of the
    :data:`HALF_WINDOW` values before it and, on the same side, from that of the ones
    after it (near an end, of those there are; the first and last value, with one side
    only, are never: there a ramp and a spike look alike)."""
    h = HALF_WINDOW
    n = values.size
    padded = np.pad(values, h, mode="constant", constant_values=np.nan)
    windows = np.lib.stride_tricks.sliding_window_view(padded, h)
    before = np.full(n, np.nan)
    after = np.full(n, np.nan)
    before[1:] = _row_medians(windows[1:n])  # values[i−h : i]
    after[:-1] = _row_medians(windows[h + 1:n + h])  # values[i+1 : i+1+h]
    z_before = (values - before) / unit
    z_after = (values - after) / unit
    with np.errstate(invalid="ignore"):  # NaN at the two ends compares False
        return (np.minimum(np.abs(z_before), np.abs(z_after)) > sigmas) \
            & (np.sign(z_before) == np.sign(z_after))


def find_spikes(residual, groups, floor: float = 0.0, measured=None):
    """Rows whose residual lies far from the running median of its neighbours'.

    Parameters
    ----------
    residual : array_like, shape (n,)
        Measured minus predicted force [N].
    groups : list of index arrays
        The rows in the order along which the force varies smoothly (time; v; k within
        one direction and dwell), one array per stretch.
    floor : float
        The noise floor [N]; the robust scale is never taken below it (a quantised or
        noise-free force has a median deviation of zero).
    measured : array_like, shape (n,), optional
        The measured force [N]. When given, a spike of the residual must be one of the
        force too (half as far out): a residual spike under a smooth force is the
        model's, from a glitch of x or t, and replacing F would not mend it.

    Returns
    -------
    spikes : numpy.ndarray of bool, shape (n,)
        True at the spikes; all False when there are none, or more than
        :data:`MAX_SHARE` of the rows (heavy-tailed noise, not spikes).
    scale : numpy.ndarray, shape (n,)
        The robust standard deviation of the residual about its neighbours' median,
        over the rows around each row [N] (zero for rows in stretches too short to
        judge).
    """
    residual = np.asanyarray(residual, dtype=float)
    if measured is not None:
        measured = np.asanyarray(measured, dtype=float)
    scale = np.zeros_like(residual)
    spikes = np.zeros(residual.size, dtype=bool)
    h = HALF_WINDOW
    for rows in groups:
        if rows.size <= 2 * h:
            continue
        r = residual[rows]
        deviation = r - running_median(r, neighbours_only=True)
        # scipy's filter: a running median over 201 rows in numpy takes seconds on a
        # long record; the ends reflect the rows there are
        spread = _MAD_TO_STD * median_filter(
            np.abs(deviation), size=2 * SCALE_HALF_WINDOW + 1, mode="reflect")
        scale[rows] = np.maximum(spread, floor)
        unit = np.where(scale[rows] > 0, scale[rows], np.inf)
        far = _stands_out(r, unit, SPIKE_SIGMAS)
        if measured is not None:
            far &= _stands_out(measured[rows], unit, SPIKE_SIGMAS / 2)
        ordinary = np.pad(np.abs(deviation) / unit <= NEIGHBOUR_SIGMAS, 1, constant_values=True)
        spikes[rows] = far & ordinary[:-2] & ordinary[2:]
    if np.count_nonzero(spikes) > max(1.0, MAX_SHARE * residual.size):
        spikes[:] = False
    return spikes, scale


def spike_rows(problem, residual, floor: float):
    """:func:`find_spikes` along the kind's regressor (:func:`.noise.orderings`). In a
    time series the measured force must spike too: its prediction runs through x and t,
    whose glitches spike the residual under a smooth force. Steady and break-away rows
    are separate measurements (their force moves too far from row to row to judge, and
    the prediction has no kinematics)."""
    measured = problem.measured if problem.kind == "timeseries" else None
    return find_spikes(residual, orderings(problem)[0], floor, measured)


def despiked_force(force, spikes, half_window: int = HALF_WINDOW):
    """``force`` with each spike replaced by the median of its neighbours (spikes
    themselves left out of that median) [N]."""
    force = np.asanyarray(force, dtype=float)
    neighbours = running_median(np.where(spikes, np.nan, force), half_window,
                                neighbours_only=True)
    return np.where(spikes, neighbours, force)


__all__ = ["HALF_WINDOW", "MAX_SHARE", "NEIGHBOUR_SIGMAS", "SPIKE_SIGMAS", "despiked_force",
           "find_spikes", "running_median", "spike_rows"]
