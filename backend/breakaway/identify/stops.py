"""Stops: where an encoder's reading cannot show whether the body turned.

A body that halts within one count (or within the reversal hysteresis of
:mod:`.kinematics`) may turn there and come back without the reading changing by the
counts a reversal needs. (E6') then runs down its presliding curve through rows the
record shows as at rest. These functions find such stretches from the reading alone and
bound, from the measured force, how much friction a turn there can have changed; the
model's side (the force along a turned path) is the problem's
(:meth:`.models.timeseries.TimeseriesProblem.resolution_errors`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: A stretch of the reading within one count boundary or the reversal hysteresis is a
#: stop when it lasts, per count it shows, this many times as long as either run of
#: one count beside it, and at least :data:`STOP_MIN_SAMPLES` samples: the body slowed
#: far below the speed it came and left with, and may have halted and turned there.
STOP_RATIO = 2.0
STOP_MIN_SAMPLES = 4
#: Noise stds of the force taken off its excursion in a stop (:func:`stop_bounds`).
BOUND_NOISE_STDS = 3.0


@njit(cache=True)
def _stop_groups(values, lengths, span, quantum, ratio, min_samples):
    """[first, stop) of the runs (``values`` of one count each, ``lengths`` samples)
    that make a stop: grouped from the left while their values stay within ``span``,
    a group is a stop where it lasts ``ratio`` times the longer run beside it per count
    it shows, and at least ``min_samples`` (a loop: records hold millions of runs)."""
    n = values.size
    firsts = np.empty(n, dtype=np.int64)
    stops = np.empty(n, dtype=np.int64)
    found = 0
    first = 0
    low = high = values[0]
    length = lengths[0]
    for j in range(1, n + 1):
        if j < n:
            new_low, new_high = min(low, values[j]), max(high, values[j])
            if new_high - new_low <= span:
                low, high = new_low, new_high
                length += lengths[j]
                continue
        before = lengths[first - 1] if first > 0 else 0
        after = lengths[j] if j < n else 0
        counts = np.floor((high - low) / quantum + 0.5) + 1.0
        if (first > 0 or j < n) and length >= min_samples \
                and length >= ratio * counts * max(before, after):
            firsts[found] = first
            stops[found] = j
            found += 1
        if j < n:
            first = j
            low = high = values[j]
            length = lengths[j]
    return firsts[:found], stops[:found]


def _merged(intervals):
    """Overlapping [start, stop) intervals joined, in order."""
    out = []
    for start, stop in sorted(intervals):
        if out and start <= out[-1][1]:
            out[-1] = (out[-1][0], max(out[-1][1], stop))
        else:
            out.append((start, stop))
    return out


def find_stops(recorded_x, blocks, quantum: float, hysteresis: float) -> list:
    """The stops of an encoder's reading.

    Parameters
    ----------
    recorded_x : array_like
        Positions as recorded, on a grid of ``quantum`` [m].
    blocks : list of (int, int)
        [start, stop) of the record's independent blocks; no stop spans two.
    quantum : float
        The encoder's count [m]; 0 (exact or noisy x) finds no stops.
    hysteresis : float
        The reversal hysteresis [m] (:data:`.kinematics.REVERSAL_STEPS` counts).

    Returns
    -------
    list of (int, int)
        [start, stop) of each stop, in order and disjoint: a stretch whose reading stays
        within one count boundary (a body at rest on it flickers between two counts)
        or within the reversal hysteresis (turns inside it are not read as turns), and
        spends, per count it shows, :data:`STOP_RATIO` times as long as the run of one
        count before and after it, and at least :data:`STOP_MIN_SAMPLES` samples; and
        each run of one count (at least as long) that the reading leaves back to the
        count it came from: the body turned inside it, when the reading cannot say.
    """
    if quantum <= 0:
        return []
    recorded_x = np.asanyarray(recorded_x, dtype=float)
    stops = []
    for a, b in blocks:
        x = recorded_x[a:b]
        edges = np.r_[0, np.flatnonzero(np.diff(x)) + 1, x.size]
        values, lengths = x[edges[:-1]], np.diff(edges)
        found = []
        for span in (1.5 * quantum, hysteresis + 0.5 * quantum):
            firsts, lasts = _stop_groups(values, lengths, span, quantum,
                                         STOP_RATIO, STOP_MIN_SAMPLES)
            found.extend(zip((a + edges[firsts]).tolist(), (a + edges[lasts]).tolist()))
        # a count the reading leaves back the way it came: the body turned inside it,
        # at a time the reading does not give, however briefly it stayed
        turns = np.flatnonzero(values[:-2] == values[2:]) + 1
        turns = turns[lengths[turns] >= STOP_MIN_SAMPLES]
        found.extend(zip((a + edges[turns]).tolist(), (a + edges[turns + 1]).tolist()))
        stops.extend(_merged(found))  # block by block: a stop never spans two
    return stops


def stop_mask(n: int, stops) -> np.ndarray | None:
    """Boolean mask of the ``n`` rows that lie in ``stops``; None where there are none."""
    if not stops:
        return None
    mask = np.zeros(n, dtype=bool)
    for a, b in stops:
        mask[a:b] = True
    mask.flags.writeable = False  # shared by every fit of the record
    return mask


def stop_bounds(F, stops) -> np.ndarray | None:
    """How much friction a turn unseen in each stop can have changed, row by row [N].

    The measured force's excursion since the stop began, less
    :data:`BOUND_NOISE_STDS` times the force's noise (robust, from its differences). A
    body at rest barely accelerates, so the force on it is its friction: a force that
    stays put while the reading does (a velocity loop holding a rest) says that nothing
    turned. Held after the stop until the next one, while the body re-engages. None
    where there are no stops.
    """
    if not stops:
        return None
    F = np.asanyarray(F, dtype=float)
    noise = 1.4826 * float(np.median(np.abs(np.diff(F)))) / np.sqrt(2.0)
    bounds = np.zeros(F.size)
    ends = [a for a, _ in stops[1:]] + [F.size]
    for (a, b), following in zip(stops, ends):
        excursion = np.abs(F[a:b] - F[a])
        bounds[a:b] = np.maximum.accumulate(
            np.maximum(excursion - BOUND_NOISE_STDS * noise, 0.0))
        bounds[b:following] = bounds[b - 1]
    return bounds


__all__ = ["STOP_MIN_SAMPLES", "STOP_RATIO", "find_stops", "stop_bounds", "stop_mask"]
