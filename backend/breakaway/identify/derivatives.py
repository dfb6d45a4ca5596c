"""Velocity and acceleration of a position record.

Every kind and effect that needs v or a takes them from here.

- Exact x (synthetic, unquantised, noise-free): ``numpy.gradient`` for v and again for
  a, so that the round trips of the presliding model stay exact.
- Measured x (an encoder's steps, or noise in x) is never differenced twice: one count
  over two samples at 1 kHz would be an acceleration of 10⁶ counts/s². Both come from
  local polynomial fits of x over windows the data choose:

  - v is each sample's least-squares slope over the narrowest centred window over
    which x spans :data:`WINDOW_RESOLUTIONS` resolutions (:func:`velocity`): fast motion
    keeps its detail (a reversal, the presliding that follows), slow motion is timed
    over several counts instead of showing one count as a spike. An encoder that holds
    its counts over several samples while the body moves (:func:`counts_held`) is read
    as the path through its edges instead (:func:`through_edges`: the body crossed a
    count boundary between the two samples that show the change), which is exact to
    within a sample's travel, and the window is the widest centred one, from
    :data:`EDGE_RESOLUTIONS` to :data:`WINDOW_RESOLUTIONS` counts, over which that
    path stays straight: a slow plateau on a coarse encoder is timed over all of it,
    and a window stops short of the turn beside it;
  - a is the curvature of a quadratic (Savitzky–Golay,
    :func:`scipy.signal.savgol_filter`; the same fit in t where the sampling is
    uneven) over at least the narrowest window in which the error of x (``q/√12`` for
    steps of q, the noise std otherwise, or what a short local fit leaves of x when
    that is larger: :func:`position_error`) contributes at most
    :data:`~.local_fits.NOISE_TO_SIGNAL` of a's RMS (:func:`~.local_fits.choose_window`): a narrower one lets the
    counts through. Each sample's window then widens for as long as the wider fits
    agree with every narrower one within their errors
    (:func:`~.local_fits.adaptive_windows`):
    where a holds steady (a constant acceleration, a slow swing) the counts' share of
    a falls as the window's length to the power 2.5, and where a changes quickly (a
    jump at a start or a braking) the window stays short.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .local_fits import (ORDER, WINDOWS, _quadratic_at, acceleration_bias, acceleration_noise,
                         adaptive_windows, choose_window, smooth_fit)

#: An adaptive window spans at least this many resolutions of x ...
WINDOW_RESOLUTIONS = 8
#: ... and at most this many samples on each side.
MAX_HALF_WINDOW = 100
#: Samples a window needs before a cubic over it says how far its slope is off.
CUBIC_SAMPLES = 7
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
def _slope(t, x, lo, hi):
    """Least-squares slope of x over the samples [lo, hi]: the counts' ±q/2 errors
    average out where an end-to-end difference would keep two of them."""
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
    return num / den


@njit(cache=True)
def _cubic_slope(t, x, i, lo, hi):
    """The slope at sample ``i`` of the least-squares cubic in t over [lo, hi], and how
    much more variance per unit variance of x it has than the straight line's slope."""
    scale = max(t[hi] - t[i], t[i] - t[lo])
    moments = np.zeros((4, 4))
    rhs = np.zeros(4)
    for j in range(lo, hi + 1):
        tau = (t[j] - t[i]) / scale
        powers = np.array([1.0, tau, tau * tau, tau * tau * tau])
        for a in range(4):
            rhs[a] += powers[a] * (x[j] - x[i])
            for b in range(4):
                moments[a, b] += powers[a] * powers[b]
    inverse = np.linalg.inv(moments)
    slope = (inverse[1, 0] * rhs[0] + inverse[1, 1] * rhs[1] + inverse[1, 2] * rhs[2]
             + inverse[1, 3] * rhs[3]) / scale
    # the straight line's slope variance is 1/Σ(τ - τ̄)²; the cubic's, its inverse's
    # element: the line is nested in the cubic, so the difference is the excess's
    centred = moments[2, 0] - moments[1, 0] ** 2 / moments[0, 0]
    excess = (inverse[1, 1] - 1.0 / centred) / scale**2
    return slope, max(excess, 0.0)


@njit(cache=True)
def _take_window(t, x, i, lo, hi, v, duration, spread, with_spread, error):
    """Sample ``i``'s v, the time it is taken over and (``with_spread``) its spread,
    from the window [lo, hi]."""
    v[i] = _slope(t, x, lo, hi)
    duration[i] = t[hi] - t[lo]
    if with_spread and hi - lo >= CUBIC_SAMPLES - 1:
        # the counts' error moves the two slopes apart too; what they add is taken off
        # (the re-reading of the record holds it), the rest is the speed's change
        cubic, excess = _cubic_slope(t, x, i, lo, hi)
        spread[i] = math.sqrt(max((cubic - v[i]) ** 2 - error**2 * excess, 0.0))


@njit(cache=True)
def _adaptive_velocity(t, x, span, max_half, with_spread, error):
    n = x.size
    v = np.empty(n)
    duration = np.empty(n)
    spread = np.zeros(n if with_spread else 0)
    for i in range(n):
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
        _take_window(t, x, i, lo, hi, v, duration, spread, with_spread, error)
    return v, duration, spread


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
def _through_edges(t, x, quantum):
    n = x.size
    edge_t = np.empty(n)
    edge_x = np.empty(n)
    inside = np.empty(n)  # the reading after each edge: the count the body is in
    edges = 0
    for i in range(1, n):
        if x[i] != x[i - 1]:
            edge_t[edges] = 0.5 * (t[i - 1] + t[i])
            edge_x[edges] = 0.5 * (x[i - 1] + x[i])
            inside[edges] = x[i]
            edges += 1
    path = x.copy()
    if edges == 0:
        return path
    # an encoder that flickers at a boundary shows a burst of edges there: an odd number
    # is one crossing, at their mean time; an even number went in and came back
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
    edges = kept
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
def _straight_velocity(t, x, quantum, max_half, path_error, with_spread, error, stride=1):
    """The slopes of :func:`_encoder_velocity`; with ``path_error < 0``, instead every
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
            if high - low >= WINDOW_RESOLUTIONS * quantum or w >= max_half:
                break
        if measure:
            continue
        _take_window(t, x, i, best_lo, best_hi, v, duration, spread, with_spread, error)
    return v, duration, spread


def _encoder_velocity(t, x, quantum, with_spread=False, error=0.0):
    """v [m/s], each window's time [s] and v's spread [m/s] of an encoder's counts
    (steps of ``quantum``): slopes of the path through the edges over the widest
    straight window (module docstring). How straight is straight is the record's own:
    the median departure of the path from a line over windows of
    :data:`MEASURE_RESOLUTIONS` counts (an encoder that flickers at its edges departs
    further)."""
    t = np.ascontiguousarray(t, dtype=float)
    path = through_edges(t, x, quantum)
    departures = _straight_velocity(t, path, quantum, MAX_HALF_WINDOW, -1.0, False, 0.0,
                                    max(x.size // DEPARTURE_SAMPLES, 1))[0]
    moving = departures[np.isfinite(departures)]
    path_error = float(np.median(moving)) if moving.size else 0.0
    return _straight_velocity(t, path, quantum, MAX_HALF_WINDOW, path_error, with_spread,
                              error)


#: The position a model runs on is a local quadratic over the narrowest window over
#: which x spans this many resolutions ...
POSITION_RESOLUTIONS = 4
#: ... and at least this many samples on each side.
MIN_POSITION_HALF_WINDOW = 2


@njit(cache=True)
def _adaptive_position(t, x, span, min_half, max_half):
    n = x.size
    p = np.empty(n)
    for i in range(n):
        w = min_half
        lo = max(i - w, 0)
        hi = min(i + w, n - 1)
        low = high = x[i]
        for j in range(lo, hi + 1):
            low = min(low, x[j])
            high = max(high, x[j])
        while high - low < span and w < max_half and (lo > 0 or hi < n - 1):
            w += 1
            lo = max(i - w, 0)
            hi = min(i + w, n - 1)
            low = min(low, x[lo], x[hi])
            high = max(high, x[lo], x[hi])
        p[i] = _quadratic_at(t, x, i, lo, hi + 1)[0]
    return p


def positions(t, x, resolution: float = 0.0):
    """The positions a model runs on [m]: x itself when it is exact; for
    an encoder's steps or a noisy x, each sample's value of a least-squares quadratic in
    t over the narrowest centred window (at least 5 samples) over which x spans
    :data:`POSITION_RESOLUTIONS` resolutions. A count holds its error while the body
    creeps through it, and (E6') is steepest just after a turn, where a model run on
    the raw counts would jump by a good part of Fs at every count (a presliding reach
    of a few counts); the fit averages the counts' errors and keeps a quick turn."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    if x.size < 2 * MIN_POSITION_HALF_WINDOW + 1 or resolution <= 0:
        return x
    return _adaptive_position(t, x, POSITION_RESOLUTIONS * resolution,
                              MIN_POSITION_HALF_WINDOW, MAX_HALF_WINDOW)


def velocity(t, x, resolution: float = 0.0, quantised: bool = False):
    """Velocity of a position record [m/s].

    ``gradient(x, t)`` when x is exact (``resolution = 0``). For a noisy x, each
    sample's velocity is the slope over the narrowest centred window over which x spans
    at least :data:`WINDOW_RESOLUTIONS` resolutions (at most :data:`MAX_HALF_WINDOW`
    samples on each side): fast motion keeps its detail, slow motion is timed over
    several resolutions instead of showing one as a spike, and jitter at rest averages
    out. For an encoder's counts held over several samples (``quantised``, steps of
    ``resolution``: :func:`counts_held`), the slope of
    the path through their edges (:func:`through_edges`) over the widest window from
    :data:`EDGE_RESOLUTIONS` to :data:`WINDOW_RESOLUTIONS` counts over which that path
    stays straight (within :data:`STRAIGHT_ERRORS` of its own error, or
    :data:`STRAIGHT_FLOOR` of a count).
    """
    return velocity_and_span(t, x, resolution, quantised)[0]


def velocity_and_span(t, x, resolution: float = 0.0, quantised: bool = False):
    """:func:`velocity` [m/s] and the time each sample's velocity is taken over [s]
    (two samples' spacing for ``numpy.gradient``)."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    if x.size < 5 or resolution <= 0:
        return np.gradient(x, t), np.gradient(t) * 2.0
    if quantised:
        return _encoder_velocity(t, x, resolution)[:2]
    return _adaptive_velocity(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW,
                              False, 0.0)[:2]


def velocity_spread(t, x, resolution: float = 0.0, error: float = 0.0,
                    quantised: bool = False) -> np.ndarray:
    """How far :func:`velocity` [m/s] lies from the body's speed where the speed changes
    within its window: the difference between the window's straight-line slope and the
    slope at the sample of a cubic over the same window, less (in quadrature) what the
    position error ``error`` [m] (std, :func:`position_error`) alone moves them apart
    by; 0 for exact x, which is not taken over windows.

    The straight line is exact where x is a quadratic over the window (a steady
    acceleration); where the speed changes otherwise (the end of a speed plateau beside
    a turn), its slope mixes both sides, and the cubic's third-order term measures by
    how much. The counts' own error of v is what a re-reading of the record shows
    (:meth:`~.models.timeseries.TimeseriesProblem.resolution_errors`); this is the
    rest, an error of the model's input that goes through the model into each row's
    error (:meth:`~.models.timeseries.TimeseriesProblem.velocity_errors`).
    """
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    if x.size < 5 or resolution <= 0:
        return np.zeros(x.size)
    if quantised:
        return _encoder_velocity(t, x, resolution, True, error)[2]
    return _adaptive_velocity(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW,
                              True, error)[2]


@dataclass(frozen=True)
class Derivatives:
    """v [m/s] and a [m/s²] of a record and how they were taken."""

    v: np.ndarray
    a: np.ndarray
    method: str  # "gradient" or "savgol"
    window: int  # samples of a's narrowest local fit (3 for numpy.gradient's difference)
    order: int
    #: the time a slow sample's velocity is taken over (median over the slower half of
    #: the moving samples, where g of E2 is steep) [s]: no lag shorter than it can be
    #: told from how v is taken
    velocity_span: float = 0.0
    #: the std of a [m/s²] that the resolution of x alone causes at the chosen window
    acceleration_noise: float = 0.0
    #: each sample's window of a's local fit [samples] (:func:`adaptive_windows`), at
    #: least :attr:`window`; None where a is not taken by local fits
    windows: np.ndarray | None = None
    #: each sample's bound on how far a may lie from the truth where a jumps [m/s²]
    #: (:func:`~.local_fits.acceleration_bias`); None where a is not taken by local fits
    bias: np.ndarray | None = None
    #: whether v is read through the edges of an encoder's counts (:func:`counts_held`)
    edges: bool = False

    @property
    def acceleration_resolved(self) -> bool:
        """Whether a stands above what the resolution of x makes of it (its RMS at
        least :data:`RESOLVED_RATIO` times that noise): an inertia needs it."""
        noise = self.acceleration_noise
        return not noise > 0 or \
            math.sqrt(float(np.mean(self.a**2))) >= RESOLVED_RATIO * noise

    def entry(self) -> dict:
        """The report's ``derivatives`` object, with how v was taken."""
        velocity_text = ("numpy.gradient" if self.method == "gradient" else
                         f"local slope over the narrowest window over which x spans "
                         f"{WINDOW_RESOLUTIONS} resolutions")
        return {"method": self.method, "window": int(self.window), "order": int(self.order),
                "velocity": velocity_text}


#: An acceleration is resolved when its RMS is at least this many times the part the
#: resolution of x makes of it.
RESOLVED_RATIO = 3.0
#: Samples of the local quadratic whose residual measures the error of x.
ERROR_WINDOW = 9


def position_error(t, x, quantum: float = 0.0, noise: float = 0.0) -> float:
    """Std of the error of a recorded position [m]: the larger of what its steps or
    noise imply (``q/√12``, the noise std) and what a local quadratic over
    :data:`ERROR_WINDOW` samples leaves of x (a real encoder's record also carries the
    rig's vibration and its electronics' jitter, which its steps do not show)."""
    x = np.asanyarray(x, dtype=float)
    implied = quantum / math.sqrt(12) if quantum > 0 else noise
    if x.size < 2 * ERROR_WINDOW:
        return implied
    left = x - smooth_fit(t, x, ERROR_WINDOW)[0]
    # a quadratic's fit takes 3 of the window's 9 degrees of freedom from white noise
    seen = math.sqrt(float(np.mean(left**2)) / (1.0 - (ORDER + 1) / ERROR_WINDOW))
    return max(implied, seen)


def counts_held(x, blocks) -> bool:
    """Whether an encoder's reading holds its counts over several samples while the
    body moves: the median run of one count, rests (runs over :data:`MAX_HALF_WINDOW`
    samples) left out, lasts at least :data:`HELD_SAMPLES` samples. Only then do its
    edges time the motion better than its samples do; where nearly every sample shows a
    new count the edges are the samples, and v is taken from them as from a noisy x."""
    runs = [np.diff(np.flatnonzero(np.diff(x[i:j]) != 0)) for i, j in blocks]
    runs = np.concatenate(runs) if runs else np.zeros(0)
    moving = runs[runs <= MAX_HALF_WINDOW]
    return moving.size > 0 and float(np.median(moving)) >= HELD_SAMPLES


def block_velocity(t, x, resolution: float, blocks, quantised: bool = False) -> np.ndarray:
    """:func:`velocity` of each independent block of a record [m/s]."""
    return np.concatenate([velocity(t[i:j], x[i:j], resolution, quantised)
                           for i, j in blocks])


def derivatives(t, x, quantum: float = 0.0, noise: float = 0.0, blocks=None,
                window: int | None = None) -> Derivatives:
    """v and a of a position record (see the module docstring).

    Parameters
    ----------
    t, x : array_like
        Times [s] and positions [m].
    quantum : float
        The step of an encoder's x [m] (0: none).
    noise : float
        The noise std of x [m] (0: none). With neither, x is exact and
        ``numpy.gradient`` is used.
    blocks : list of (start, stop), optional
        Independent records within the arrays (a screened series); each is
        differentiated on its own.
    window : int, optional
        The acceleration's window [samples]; chosen from the data
        (:func:`choose_window`) by default.
    """
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    blocks = blocks or [(0, x.size)]
    resolution = max(quantum, noise)
    if resolution <= 0 or x.size < WINDOWS[0]:
        v = np.concatenate([np.gradient(x[i:j], t[i:j]) for i, j in blocks])
        a = np.concatenate([np.gradient(v[i:j], t[i:j]) for i, j in blocks])
        return Derivatives(v, a, "gradient", 3, 2, _span(v, np.gradient(t) * 2.0))
    if window is None:
        first, last = max(blocks, key=lambda block: block[1] - block[0])
        error = position_error(t[first:last], x[first:last], quantum, noise)
        window = choose_window(t[first:last], x[first:last], error)
    edges = quantum >= noise and counts_held(x, blocks)
    parts = [velocity_and_span(t[i:j], x[i:j], resolution, edges) for i, j in blocks]
    v = np.concatenate([part[0] for part in parts])
    spans = np.concatenate([part[1] for part in parts])
    first, last = max(blocks, key=lambda block: block[1] - block[0])
    error = position_error(t[first:last], x[first:last], quantum, noise)
    a, windows, bias = np.empty(x.size), np.full(x.size, 3), np.zeros(x.size)
    for i, j in blocks:
        if j - i >= WINDOWS[0]:
            a[i:j], windows[i:j] = adaptive_windows(t[i:j], x[i:j], error, window)
            bias[i:j] = acceleration_bias(t[i:j], x[i:j], error, window)
        else:
            a[i:j] = np.gradient(v[i:j], t[i:j])
    noise_a = acceleration_noise(window, error, float(np.median(np.diff(t[first:last]))))
    return Derivatives(v, a, "savgol", window, ORDER, _span(v, spans), noise_a, windows, bias,
                       edges)


def _span(v, spans) -> float:
    """The median span of the slower half of the moving samples [s]."""
    speed = np.abs(v)
    moving = speed > 0
    if not moving.any():
        return float(np.median(spans))
    return float(np.median(spans[moving & (speed <= np.median(speed[moving]))]))


__all__ = ["Derivatives", "EDGE_RESOLUTIONS", "MAX_HALF_WINDOW", "POSITION_RESOLUTIONS",
           "WINDOW_RESOLUTIONS", "block_velocity", "derivatives", "position_error",
           "positions", "through_edges", "velocity", "velocity_and_span", "velocity_spread"]
