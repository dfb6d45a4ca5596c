"""The speed of an encoder that holds its counts over several samples, read through its
edges.

Where the reading changes, the body crossed the boundary between the two counts between
the two samples that show it: those crossings are timed to within a sample, where the
counts themselves are only placed to within a count. :func:`through_edges` draws the path
through them, and :func:`encoder_velocity` takes each sample's v as that path's slope
over the widest centred window, from :data:`EDGE_RESOLUTIONS` counts up, over which it
stays straight: a slow plateau on a coarse encoder is timed over all of it, and a window
stops short of the turn beside it. :func:`chord_departure` says how far that v may lie
from the speed where the speed changed inside the counts (the chords from edge to edge
read it otherwise). :func:`counts_held` says whether a record's reading is such
(:mod:`.derivatives` decides with it how v is taken).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .local_fits import _take_window

#: The median run of one count, in samples, from which an encoder's edges time its
#: motion (:func:`counts_held`).
HELD_SAMPLES = 2
#: v through an encoder's edges is taken over at least this many counts (two edges'
#: times fix a speed to within a sample) ...
EDGE_RESOLUTIONS = 1
#: ... widening while the window's new ends depart from its straight line by at most
#: this many of the path's own errors (a sample's travel over √12, a count's at most,
#: or what the path departs by where it is straight) ...
STRAIGHT_ERRORS = 3.0
#: ... or this share of a count, the least an encoder's edges are placed to.
STRAIGHT_FLOOR = 0.05
#: What the path departs by where it is straight is the median RMS departure from the
#: line over windows of this many counts ...
MEASURE_RESOLUTIONS = 3
#: ... about this many samples, evenly spread.
DEPARTURE_SAMPLES = 1000


@njit(cache=True)
def _edge_slope(before, after):
    """The path's slope at an edge from the chords on either side: their harmonic mean
    where the body passed on (Fritsch–Carlson: it never overshoots), the moving side's
    where the other stays within a count (the body entered it to turn there), 0 where
    the chords turn."""
    if before == 0.0:
        return after
    if after == 0.0:
        return before
    if before * after < 0.0:
        return 0.0
    return 2.0 / (1.0 / before + 1.0 / after)


@njit(cache=True)
def _edges(t, x):
    """The times [s] and positions [m] of the crossings of an encoder's count
    boundaries, and the reading after each (the count the body is in): where the reading
    changes, at the middle of the two samples that show it. An encoder that flickers at
    a boundary shows a burst of edges there: an odd number is one crossing, at their
    mean time; an even number went in and came back."""
    n = x.size
    edge_t = np.empty(n)
    edge_x = np.empty(n)
    inside = np.empty(n)
    edges = 0
    for i in range(1, n):
        if x[i] != x[i - 1]:
            edge_t[edges] = 0.5 * (t[i - 1] + t[i])
            edge_x[edges] = 0.5 * (x[i - 1] + x[i])
            inside[edges] = x[i]
            edges += 1
    kept = 0
    first = 0
    while first < edges:
        last = first
        while last + 1 < edges and edge_x[last + 1] == edge_x[first]:
            last += 1
        if (last - first) % 2 == 0:
            edge_t[kept] = np.mean(edge_t[first:last + 1])
            edge_x[kept] = edge_x[first]
            inside[kept] = inside[last]
            kept += 1
        else:
            for k in (first, last):
                edge_t[kept], edge_x[kept], inside[kept] = edge_t[k], edge_x[k], inside[k]
                kept += 1
        first = last + 1
    return edge_t[:kept], edge_x[:kept], inside[:kept]


@njit(cache=True)
def _through_edges(t, x, quantum):
    n = x.size
    edge_t, edge_x, inside = _edges(t, x)
    edges = edge_t.size
    path = x.copy()
    if edges == 0:
        return path
    chords = np.zeros(max(edges - 1, 1))
    for k in range(edges - 1):
        chords[k] = (edge_x[k + 1] - edge_x[k]) / (edge_t[k + 1] - edge_t[k])
    slopes = np.zeros(edges)
    for k in range(edges):
        before = chords[k - 1] if k > 0 else (chords[0] if edges > 1 else 0.0)
        after = chords[k] if k < edges - 1 else before
        slopes[k] = _edge_slope(before, after)
    k = 0
    half = 0.5 * quantum
    for i in range(n):
        while k < edges and edge_t[k] <= t[i]:
            k += 1
        if k == 0:
            # before the first edge and after the last the reading says no more than
            # that the body was within a count: a record that starts at rest stays so
            path[i] = edge_x[0]
        elif k == edges:
            path[i] = edge_x[edges - 1]
        else:
            h = edge_t[k] - edge_t[k - 1]
            s = (t[i] - edge_t[k - 1]) / h
            hermite = (edge_x[k - 1] * (2 * s**3 - 3 * s**2 + 1)
                       + h * slopes[k - 1] * (s**3 - 2 * s**2 + s)
                       + edge_x[k] * (-2 * s**3 + 3 * s**2)
                       + h * slopes[k] * (s**3 - s**2))
            # the body stays within the count the reading shows
            count = inside[k - 1]
            path[i] = min(max(hermite, count - half), count + half)
    return path


def through_edges(t, x, quantum: float | None = None) -> np.ndarray:
    """The path [m] through the edges of an encoder's counts ``x`` [m] (steps of
    ``quantum``, by default the smallest change) at times ``t`` [s]: where the reading
    changes, the body crossed the boundary between the two counts between the two
    samples, and from one crossing to the next it moves along the cubic with the
    slopes the chords beside give it (:func:`_edge_slope`), never out of the count the
    reading shows. A plateau read over a few counts is then a straight line, not a
    staircase whose least-squares slope depends on where the window cuts its steps;
    a turn inside a count goes in at the speed it came and out at the speed it left.
    Before the first edge and after the last it is held at that edge."""
    x = np.ascontiguousarray(x, dtype=float)
    if quantum is None:
        steps = np.abs(np.diff(x))
        quantum = float(np.min(steps[steps > 0])) if np.any(steps > 0) else 0.0
    return _through_edges(np.ascontiguousarray(t, dtype=float), x, float(quantum))


@njit(cache=True)
def _straight_velocity(t, x, quantum, max_counts, max_half, path_error, with_spread, error,
                       stride=1):
    """The slopes of :func:`encoder_velocity`; with ``path_error < 0``, instead every
    ``stride``-th sample's RMS departure of the path from the line over its narrowest
    window spanning :data:`MEASURE_RESOLUTIONS` counts (NaN elsewhere)."""
    n = x.size
    measure = path_error < 0
    min_span = (MEASURE_RESOLUTIONS if measure else EDGE_RESOLUTIONS) * quantum
    v = np.full(n, np.nan)
    duration = np.empty(n)
    spread = np.zeros(n if with_spread else 0)
    for i in range(0, n, stride if measure else 1):
        # running sums of the window about sample i, for its line's residual
        count = 1.0
        st = sx = stt = stx = sxx = 0.0
        lo = hi = i
        low = high = x[i]
        best_lo, best_hi = max(i - 1, 0), min(i + 1, n - 1)
        w = 0
        while True:
            w += 1
            new_lo, new_hi = max(i - w, 0), min(i + w, n - 1)
            if new_lo == lo and new_hi == hi:
                break
            for j in (new_lo, new_hi):
                if lo <= j <= hi:
                    continue  # an end of the record: the window grows on one side
                dt, dx = t[j] - t[i], x[j] - x[i]
                count += 1.0
                st += dt
                sx += dx
                stt += dt * dt
                stx += dt * dx
                sxx += dx * dx
            lo, hi = new_lo, new_hi
            low = min(low, x[lo], x[hi])
            high = max(high, x[lo], x[hi])
            centred_tt = stt - st * st / count
            centred_tx = stx - st * sx / count
            spans = high - low >= min_span and w >= 2
            if measure and spans:
                centred_xx = sxx - sx * sx / count
                rss = max(centred_xx - centred_tx**2 / centred_tt, 0.0)
                v[i] = math.sqrt(rss / count)
                break
            # the path's own error: a sample's travel (an edge is timed to within a
            # sample; never more than a count), or what the record's path departs by
            # where it is straight (an encoder that flickers at its edges); a departure
            # shows first at the window's new ends
            travel = min(abs(x[hi] - x[lo]) / (hi - lo), quantum) / math.sqrt(12.0)
            tolerance = max(STRAIGHT_ERRORS * max(travel, path_error),
                            STRAIGHT_FLOOR * quantum)
            if not measure and spans and centred_tt > 0:
                slope = centred_tx / centred_tt
                mean_t, mean_x = st / count, sx / count
                departure = max(abs(x[lo] - x[i] - mean_x - slope * (t[lo] - t[i] - mean_t)),
                                abs(x[hi] - x[i] - mean_x - slope * (t[hi] - t[i] - mean_t)))
                if departure > tolerance:
                    break
            best_lo, best_hi = lo, hi
            if high - low >= max_counts * quantum or w >= max_half:
                break
        if measure:
            continue
        _take_window(t, x, i, best_lo, best_hi, v, duration, spread, with_spread, error)
    return v, duration, spread


def encoder_velocity(t, x, quantum, max_counts, max_half, with_spread=False, error=0.0):
    """v [m/s], each window's time [s] and v's spread [m/s] of an encoder's counts
    (steps of ``quantum``): slopes of the path through the edges over the widest
    straight window of :data:`EDGE_RESOLUTIONS` to ``max_counts`` counts and at most
    ``max_half`` samples a side (module docstring). How straight is straight is the record's own:
    the median departure of the path from a line over windows of
    :data:`MEASURE_RESOLUTIONS` counts (an encoder that flickers at its edges departs
    further)."""
    t = np.ascontiguousarray(t, dtype=float)
    path = through_edges(t, x, quantum)
    departures = _straight_velocity(t, path, quantum, max_counts, max_half, -1.0, False, 0.0,
                                    max(x.size // DEPARTURE_SAMPLES, 1))[0]
    moving = departures[np.isfinite(departures)]
    path_error = float(np.median(moving)) if moving.size else 0.0
    return _straight_velocity(t, path, quantum, max_counts, max_half, path_error,
                              with_spread, error)


#: A chord between two edges is timed to within a sample at each end; v departs from
#: the chords' reading by more than this many of their timing errors before the
#: departure counts (:func:`chord_departure`).
CHORD_ERRORS = 2.0


def chord_departure(t, x, v) -> np.ndarray:
    """How far each sample's v [m/s] departs from the chords of an encoder's counts
    ``x`` [m] at times ``t`` [s]: a chord from edge to edge is the mean speed over its
    count, the speed at its middle where the speed changes steadily, and between the
    middles of two counts the speed runs along the line between their chords. Where v
    and that reading of the same counts differ by more than :data:`CHORD_ERRORS` of
    the chords' timing errors, the speed changed inside the counts in a way neither
    resolves (the end of a plateau before a turn, a change of speed inside one count)
    and v is uncertain by the difference. 0 on a plateau and under a steady
    acceleration, where both readings agree."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    v = np.asanyarray(v, dtype=float)
    edge_t, edge_x, _ = _edges(t, x)
    if edge_t.size < 3:
        return np.zeros(x.size)
    step = float(np.median(np.diff(t)))
    duration = np.diff(edge_t)
    chords = np.diff(edge_x) / duration
    # each edge is placed uniformly within its sample: std step/√12, two of them
    errors = np.abs(chords) * step / (math.sqrt(6.0) * duration)
    middles = 0.5 * (edge_t[1:] + edge_t[:-1])
    reading = np.interp(t, middles, chords)
    allowance = CHORD_ERRORS * np.interp(t, middles, errors)
    return np.maximum(np.abs(v - reading) - allowance, 0.0)


def counts_held(x, blocks, rest: int) -> bool:
    """Whether an encoder's reading holds its counts over several samples while the
    body moves: the median run of one count, rests (runs over ``rest`` samples) left
    out, lasts at least :data:`HELD_SAMPLES` samples. Only then do its
    edges time the motion better than its samples do; where nearly every sample shows a
    new count the edges are the samples, and v is taken from them as from a noisy x."""
    runs = [np.diff(np.flatnonzero(np.diff(x[i:j]) != 0)) for i, j in blocks]
    runs = np.concatenate(runs) if runs else np.zeros(0)
    moving = runs[runs <= rest]
    return moving.size > 0 and float(np.median(moving)) >= HELD_SAMPLES


__all__ = ["CHORD_ERRORS", "DEPARTURE_SAMPLES", "EDGE_RESOLUTIONS", "HELD_SAMPLES",
           "MEASURE_RESOLUTIONS",
           "STRAIGHT_ERRORS", "STRAIGHT_FLOOR", "chord_departure", "counts_held",
           "encoder_velocity",
           "through_edges"]
