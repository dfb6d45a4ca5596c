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
    over several counts instead of showing one count as a spike, and on an encoder's
    steps the window widens for as long as x stays on its line (a steady speed is timed
    over the whole of its straight run). An encoder that holds
    its counts over several samples while the body moves is read as the path through
    its edges instead (:mod:`.encoder_edges`: the body crossed a count boundary between
    the two samples that show the change), which is exact to within a sample's travel,
    and the window is the widest centred one, up to :data:`WINDOW_RESOLUTIONS` counts,
    over which that path stays straight: a slow plateau on a coarse encoder is timed over all of it,
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

from .encoder_edges import STRAIGHT_ERRORS, chord_departure, counts_held, encoder_velocity
from .local_fits import (ORDER, WINDOWS, _quadratic_at, acceleration_bias,
                         acceleration_noise, adaptive_windows, choose_window, smooth_fit)
from .velocity_windows import _adaptive_velocity, _velocity_at

#: An adaptive window spans at least this many resolutions of x ...
WINDOW_RESOLUTIONS = 8
#: ... and at most this many samples on each side.
MAX_HALF_WINDOW = 100
#: A record of fewer samples has its v by ``numpy.gradient``.
SHORTEST_WINDOWED = 5

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


def velocity(t, x, resolution: float = 0.0, quantised: bool = False, widen: float = 0.0):
    """Velocity of a position record [m/s].

    ``gradient(x, t)`` when x is exact (``resolution = 0``). For a noisy x, each
    sample's velocity is the slope over the narrowest centred window over which x spans
    at least :data:`WINDOW_RESOLUTIONS` resolutions (at most :data:`MAX_HALF_WINDOW`
    samples on each side): fast motion keeps its detail, slow motion is timed over
    several resolutions instead of showing one as a spike, and jitter at rest averages
    out. With ``widen`` (an encoder's steps: the std of its reading's error [m],
    :func:`position_error`) that window grows a sample a side at a time while both new
    ends stay within :data:`~.encoder_edges.STRAIGHT_ERRORS` of those errors of the
    widened window's line (:mod:`.velocity_windows`): a steady speed is timed over the
    whole of its straight run. Over the narrowest window alone a count more or less is an error
    of several per cent, and as the counts' phase drifts against the samples it holds
    for tens of samples, an error of the steady speed the fit reads as friction; a white
    noise of x leaves no such error, and its windows are not widened. For an encoder's
    counts held over several samples (``quantised``, steps of ``resolution``:
    :func:`~.encoder_edges.counts_held`), the slope of the path through their edges over
    the widest window of up to :data:`WINDOW_RESOLUTIONS` counts over which that path
    stays straight (:func:`~.encoder_edges.encoder_velocity`).
    """
    return velocity_and_span(t, x, resolution, quantised, widen)[0]


def velocity_and_span(t, x, resolution: float = 0.0, quantised: bool = False,
                      widen: float = 0.0):
    """:func:`velocity` [m/s] and the time each sample's velocity is taken over [s]
    (two samples' spacing for ``numpy.gradient``)."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    if x.size < SHORTEST_WINDOWED or resolution <= 0:
        return np.gradient(x, t), np.gradient(t) * 2.0
    if quantised:
        return encoder_velocity(t, x, resolution, WINDOW_RESOLUTIONS, MAX_HALF_WINDOW)[:2]
    return _adaptive_velocity(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW,
                              False, 0.0, STRAIGHT_ERRORS * widen)[:2]


def velocity_and_reach(t, x, resolution: float, widen: float = 0.0):
    """:func:`velocity` [m/s] of a record whose v is taken over adaptive windows (x
    neither exact nor read through an encoder's edges, at least 5 samples), and each
    sample's reach: the first and last sample that its window read, shape (n, 2)."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    v = np.empty(x.size)
    reach = np.empty((x.size, 2), dtype=np.int64)
    _velocity_at(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW,
                 STRAIGHT_ERRORS * widen, np.arange(x.size), v, reach)
    return v, reach


def velocity_at(t, x, resolution: float, rows, known, widen: float = 0.0) -> np.ndarray:
    """:func:`velocity` [m/s] of such a record at ``rows``, ``known`` elsewhere (where
    each sample's window reads what it read on a record whose v is ``known``)."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    v = np.array(known, dtype=float)
    _velocity_at(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW,
                 STRAIGHT_ERRORS * widen, np.asarray(rows, dtype=np.int64), v,
                 np.empty((x.size, 2), dtype=np.int64))
    return v


def velocity_spread(t, x, resolution: float = 0.0, error: float = 0.0,
                    quantised: bool = False, widen: float = 0.0) -> np.ndarray:
    """How far :func:`velocity` [m/s] lies from the body's speed where the speed changes
    within its window: the difference between the window's straight-line slope and the
    slope at the sample of a cubic over the same window, less (in quadrature) what the
    position error ``error`` [m] (std, :func:`position_error`) alone moves them apart
    by; 0 for exact x, which is not taken over windows.

    The straight line is exact where x is a quadratic over the window (a steady
    acceleration); where the speed changes otherwise (the end of a speed plateau beside
    a turn), its slope mixes both sides, and the cubic's third-order term measures by
    how much. Read through an encoder's edges (``quantised``), the spread is at least
    how far v departs from the chords' own reading of the speed
    (:func:`~.encoder_edges.chord_departure`): a change of speed inside the counts,
    which no window of the path through them bends at. The counts' own error of v is
    what a re-reading of the record shows
    (:meth:`~.models.timeseries.TimeseriesProblem.resolution_errors`); this is the
    rest, an error of the model's input that goes through the model into each row's
    error (:meth:`~.models.timeseries.TimeseriesProblem.velocity_errors`). ``widen``
    as for :func:`velocity`, whose windows the spread is taken over.
    """
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    if x.size < SHORTEST_WINDOWED or resolution <= 0:
        return np.zeros(x.size)
    if quantised:
        v, _, spread = encoder_velocity(t, x, resolution, WINDOW_RESOLUTIONS,
                                        MAX_HALF_WINDOW, True, error)
        return np.maximum(spread, chord_departure(t, x, v))
    return _adaptive_velocity(t, x, WINDOW_RESOLUTIONS * resolution, MAX_HALF_WINDOW,
                              True, error, STRAIGHT_ERRORS * widen)[2]


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
    #: whether v is read through an encoder's edges (:func:`~.encoder_edges.counts_held`)
    edges: bool = False
    #: the std of an encoder's reading error [m] (:func:`position_error`) by which v's
    #: windows widen at a steady speed (:func:`velocity`); 0 for exact or noisy x
    step_error: float = 0.0

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


def block_velocity(t, x, resolution: float, blocks, quantised: bool = False,
                   widen: float = 0.0) -> np.ndarray:
    """:func:`velocity` of each independent block of a record [m/s]."""
    return np.concatenate([velocity(t[i:j], x[i:j], resolution, quantised, widen)
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
    first, last = max(blocks, key=lambda block: block[1] - block[0])
    error = position_error(t[first:last], x[first:last], quantum, noise)
    if window is None:
        window = choose_window(t[first:last], x[first:last], error)
    edges = quantum >= noise and counts_held(x, blocks, MAX_HALF_WINDOW)
    # an encoder's steps: a steady speed is timed over all of its straight run
    widen = error if 0 < quantum and noise <= quantum else 0.0
    parts = [velocity_and_span(t[i:j], x[i:j], resolution, edges, widen) for i, j in blocks]
    v = np.concatenate([part[0] for part in parts])
    spans = np.concatenate([part[1] for part in parts])
    a, windows, bias = np.empty(x.size), np.full(x.size, 3), np.zeros(x.size)
    for i, j in blocks:
        if j - i >= WINDOWS[0]:
            a[i:j], windows[i:j] = adaptive_windows(t[i:j], x[i:j], error, window)
            bias[i:j] = acceleration_bias(t[i:j], x[i:j], error, window)
        else:
            a[i:j] = np.gradient(v[i:j], t[i:j])
    noise_a = acceleration_noise(window, error, float(np.median(np.diff(t[first:last]))))
    return Derivatives(v, a, "savgol", window, ORDER, _span(v, spans), noise_a, windows, bias,
                       edges, widen)


def _span(v, spans) -> float:
    """The median span of the slower half of the moving samples [s]."""
    speed = np.abs(v)
    moving = speed > 0
    if not moving.any():
        return float(np.median(spans))
    return float(np.median(spans[moving & (speed <= np.median(speed[moving]))]))


__all__ = ["Derivatives", "MAX_HALF_WINDOW", "POSITION_RESOLUTIONS", "SHORTEST_WINDOWED",
           "WINDOW_RESOLUTIONS", "block_velocity", "derivatives", "position_error",
           "positions", "velocity", "velocity_and_reach", "velocity_and_span", "velocity_at",
           "velocity_spread"]
