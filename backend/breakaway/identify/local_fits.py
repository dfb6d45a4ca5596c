"""Local polynomial fits of a position record: the acceleration's windows.

a is the curvature of a quadratic (Savitzky–Golay, :func:`scipy.signal.savgol_filter`;
the same fit in t where the sampling is uneven, :func:`local_fit`) over at least the
narrowest window in which the error of x contributes at most :data:`NOISE_TO_SIGNAL` of
a's RMS (:func:`choose_window`); each sample's window then widens for as long as the
wider fits agree with every narrower one within their errors (:func:`adaptive_windows`).
:mod:`.derivatives` takes v and a from here; v is a least-squares slope over a window
(:func:`_take_window`, with a cubic's slope beside it for how far the line is off).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.ndimage import maximum_filter1d
from scipy.signal import oaconvolve, savgol_coeffs, savgol_filter

#: Degree of the local polynomial: a quadratic gives the slope and the curvature.
ORDER = 2
#: The resolution of x may contribute at most this share of a's RMS: an inertia m_e
#: fitted on such an a is biased low by about the share squared (1 %).
NOISE_TO_SIGNAL = 0.1
#: Windows tried [samples], odd, about √2 apart.
WINDOWS = (5, 7, 9, 13, 17, 25, 33, 47, 65, 93, 129, 181, 257, 363, 513)
#: Sampling is uniform when every step is within this share of the median step.
UNIFORM_TOLERANCE = 1e-3
#: Rows the window is chosen on (a long record is judged on evenly spread samples).
CHOICE_ROWS = 200_000


@njit(cache=True)
def _quadratic_at(t, x, i, lo, hi):
    """Coefficients (c0, c1, c2) of the least-squares x ≈ c0 + c1·u + c2·u², u = t − t_i,
    over samples lo … hi − 1 (Cramer's rule on the 3 × 3 normal equations); x_i and
    zeros when they are singular."""
    s0 = s1 = s2 = s3 = s4 = 0.0
    b0 = b1 = b2 = 0.0
    for j in range(lo, hi):
        u = t[j] - t[i]
        u2 = u * u
        s0 += 1.0
        s1 += u
        s2 += u2
        s3 += u2 * u
        s4 += u2 * u2
        b0 += x[j]
        b1 += u * x[j]
        b2 += u2 * x[j]
    det = s0 * (s2 * s4 - s3 * s3) - s1 * (s1 * s4 - s3 * s2) + s2 * (s1 * s3 - s2 * s2)
    if det == 0.0:
        return x[i], 0.0, 0.0
    c0 = (b0 * (s2 * s4 - s3 * s3) - s1 * (b1 * s4 - s3 * b2) + s2 * (b1 * s3 - s2 * b2)) / det
    c1 = (s0 * (b1 * s4 - s3 * b2) - b0 * (s1 * s4 - s3 * s2) + s2 * (s1 * b2 - b1 * s2)) / det
    c2 = (s0 * (s2 * b2 - b1 * s3) - s1 * (s1 * b2 - b1 * s2) + b0 * (s1 * s3 - s2 * s2)) / det
    return c0, c1, c2


def _uniform_step(t) -> float | None:
    """The sampling interval when ``t`` is uniformly sampled, else None."""
    steps = np.diff(t)
    dt = float(np.median(steps))
    if dt > 0 and float(np.max(np.abs(steps - dt))) <= UNIFORM_TOLERANCE * dt:
        return dt
    return None


@njit(cache=True)
def _local_quadratic(t, x, half):
    """Value, slope and curvature of a least-squares quadratic in t over each sample's
    window of ``2·half + 1`` samples (shifted inwards at the ends), for uneven sampling."""
    n = x.size
    p = np.empty(n)
    v = np.empty(n)
    a = np.empty(n)
    for i in range(n):
        lo = min(max(i - half, 0), max(n - 2 * half - 1, 0))
        hi = min(lo + 2 * half + 1, n)
        p[i], v[i], c2 = _quadratic_at(t, x, i, lo, hi)
        a[i] = 2.0 * c2
    return p, v, a


def local_fit(t, x, window: int, order: int = ORDER):
    """v and a of ``x(t)`` from a local polynomial of ``order`` over ``window`` samples.

    Parameters
    ----------
    t, x : array_like
        Times [s] (increasing) and positions [m].
    window : int
        Odd number of samples of each fit.
    order : int
        Degree of the polynomial (2 where the sampling is uneven).

    Returns
    -------
    v, a : numpy.ndarray
        [m/s], [m/s²].
    """
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    return smooth_fit(t, x, window, order)[1:]


def smooth_fit(t, x, window: int, order: int = ORDER):
    """Position, velocity and acceleration of ``x(t)`` from a local polynomial of
    ``order`` over ``window`` samples ([m], [m/s], [m/s²])."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    window = min(window, x.size if x.size % 2 else x.size - 1)
    dt = _uniform_step(t)
    if dt is None:
        return _local_quadratic(t, x, window // 2)
    return tuple(savgol_filter(x, window, order, deriv=k, delta=dt, mode="interp")
                 for k in (0, 1, 2))


#: Windows of more samples than this are convolved by FFT (overlap-add): a direct
#: convolution costs the window's length per sample.
FFT_WINDOW = 64


def curvature_fit(t, x, window: int) -> np.ndarray:
    """a [m/s²] of ``x(t)`` alone from a local quadratic over ``window`` samples (what
    :func:`local_fit` gives, without its velocity): on even sampling a Savitzky–Golay
    filter, the long windows by FFT, the ends by the quadratic of the first and last
    window as ``savgol_filter``'s ``mode="interp"`` does."""
    t = np.ascontiguousarray(t, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    window = min(window, x.size if x.size % 2 else x.size - 1)
    dt = _uniform_step(t)
    if dt is None:
        return _local_quadratic(t, x, window // 2)[2]
    if window <= FFT_WINDOW or x.size < 4 * window:
        return savgol_filter(x, window, ORDER, deriv=2, delta=dt, mode="interp")
    half = window // 2
    coeffs = savgol_coeffs(window, ORDER, deriv=2, delta=dt, use="dot")
    a = np.empty(x.size)
    a[half:-half] = oaconvolve(x, coeffs[::-1], mode="valid")
    a[:half] = savgol_filter(x[:window], window, ORDER, deriv=2, delta=dt, mode="interp")[:half]
    a[-half:] = savgol_filter(x[-window:], window, ORDER, deriv=2, delta=dt,
                              mode="interp")[-half:]
    return a


def acceleration_noise(window: int, resolution: float, dt: float, order: int = ORDER) -> float:
    """Std of a [m/s²] that a white error of ``resolution`` in x causes in a local fit
    of ``window`` samples at interval ``dt``."""
    coeffs = savgol_coeffs(window, order, deriv=2, delta=dt, use="dot")
    return resolution * float(np.sqrt(np.dot(coeffs, coeffs)))


def choose_window(t, x, resolution: float) -> int:
    """The narrowest window of :data:`WINDOWS` in which the resolution of x [m]
    contributes at most :data:`NOISE_TO_SIGNAL` of a's RMS (the widest that fits the
    record when none does)."""
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    stride = max(1, x.size // CHOICE_ROWS)
    dt = float(np.median(np.diff(t)))
    fitting = [w for w in WINDOWS if w <= max(x.size // 4, WINDOWS[0])]
    for window in fitting:
        a = curvature_fit(t, x, window)
        noise = acceleration_noise(window, resolution, dt)
        signal = math.sqrt(max(float(np.mean(a[::stride] ** 2)) - noise**2, 0.0))
        if noise <= NOISE_TO_SIGNAL * signal:
            return window
    return fitting[-1]


#: A wider window's a must lie within this many of its standard errors (what the error
#: of x makes of it) of every narrower window's: the intersection of confidence
#: intervals rule of adaptive smoothing (Goldenshluger & Nemirovski 1997; Katkovnik
#: 1999). Three standard errors, as elsewhere in this engine: a window is widened over a
#: real change of a only where that change is within the noise of the narrower fits.
AGREEMENT = 3.0


def adaptive_windows(t, x, error: float, narrowest: int) -> tuple[np.ndarray, np.ndarray]:
    """Each sample's acceleration [m/s²] and window [samples]: the widest window of
    :data:`WINDOWS`, from ``narrowest`` up, whose local fit's a lies within
    :data:`AGREEMENT` standard errors of every narrower one's (the intervals
    a ± AGREEMENT·std of all windows so far still intersect); the std is what a white
    error of ``error`` [m] in x makes of a (:func:`acceleration_noise`).

    A steady a is thus taken over a long window, where x's resolution hardly shows,
    and a quick change over a short one, which keeps it. Once the intervals part, the
    sample keeps the last window at which they met; a window longer than the record is
    its whole length, as in :func:`curvature_fit`. (Windows that end or start at the
    sample, which keep widening beside a jump of a, were tried: they mended one more
    heavy carriage and put a ramp's corner, a jump of a the centred window spreads,
    into an inertia and a lag on two joints.)"""
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    dt = float(np.median(np.diff(t)))
    tried = [w for w in WINDOWS if narrowest <= w <= max(x.size // 4, narrowest)] or [narrowest]
    low = np.full(x.size, -np.inf)
    high = np.full(x.size, np.inf)
    agreeing = np.ones(x.size, dtype=bool)
    a = windows = None
    for window in tried:
        a_w = curvature_fit(t, x, window)
        spread = AGREEMENT * acceleration_noise(window, error, dt)
        np.maximum(low, a_w - spread, out=low)
        np.minimum(high, a_w + spread, out=high)
        agreeing &= low <= high
        if a is None:
            a, windows = a_w, np.full(x.size, window)
        else:
            a[agreeing] = a_w[agreeing]
            windows[agreeing] = window
        if not agreeing.any():
            break
    return a, windows


def acceleration_bias(t, x, error: float, narrowest: int) -> np.ndarray:
    """How far each sample's a [m/s²] may lie from the truth where a jumps (a heavy
    body's start, its braking): the change of a across the narrowest window (from the
    fit that ends half a window before the sample to the one that starts half a window
    after it) in excess of the changes over the windows beside it and of
    :data:`AGREEMENT` times what x's error makes of such a difference, and the largest
    of it within half a window either side.

    A centred quadratic spreads a jump of a over its window, and no window narrower
    than the noise allows reads it: the rows within a window of the jump carry an error
    of up to the jump (tens of newtons times a carriage's mass, on a load cell of half
    a newton). A smooth change is read without such a bias (a centred quadratic's
    curvature follows a linear change of a exactly), and it changes a beside the
    window as much as across it: only a change that its neighbours do not share is a
    jump. Where a holds steady or changes smoothly the bias is 0."""
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    half = narrowest // 2
    if x.size < narrowest + 6 * half:
        return np.zeros(x.size)
    a = curvature_fit(t, x, narrowest)
    rows = np.arange(x.size)

    def at(shift):
        return a[np.clip(rows + shift, 0, x.size - 1)]

    across = np.abs(at(half) - at(-half))
    beside = np.maximum(np.abs(at(-half) - at(-3 * half)), np.abs(at(3 * half) - at(half)))
    dt = float(np.median(np.diff(t)))
    noise = math.sqrt(2.0) * acceleration_noise(narrowest, error, dt)
    excess = np.maximum(across - beside - AGREEMENT * noise, 0.0)
    return maximum_filter1d(excess, 2 * half + 1, mode="nearest")


def acceleration_at(t, x, windows) -> np.ndarray:
    """a [m/s²] of ``x(t)``, each sample's from the local fit over its own window of
    ``windows`` [samples] (those :func:`adaptive_windows` chose for another reading of
    the same samples)."""
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    a = np.empty(x.size)
    for window in np.unique(windows):
        rows = windows == window
        a[rows] = curvature_fit(t, x, int(window))[rows]
    return a


#: Samples a window needs before a cubic over it says how far its slope is off.
CUBIC_SAMPLES = 7


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
    # the normal equations' sums in scalars (τ = (t - t_i)/scale): kept in registers,
    # where a 4×4 array updated per sample costs more than the products themselves
    s0 = s1 = s2 = s3 = s4 = s5 = s6 = 0.0
    r0 = r1 = r2 = r3 = 0.0
    for j in range(lo, hi + 1):
        tau = (t[j] - t[i]) / scale
        tau2 = tau * tau
        tau3 = tau2 * tau
        dx = x[j] - x[i]
        s0 += 1.0
        s1 += tau
        s2 += tau2
        s3 += tau3
        s4 += tau2 * tau2
        s5 += tau2 * tau3
        s6 += tau3 * tau3
        r0 += dx
        r1 += tau * dx
        r2 += tau2 * dx
        r3 += tau3 * dx
    # column 1 of the moments' inverse (its row 1: they are symmetric) by Cholesky in
    # scalars, where LAPACK's inverse called per sample costs eight times the sums;
    # CUBIC_SAMPLES distinct times keep the moments positive definite
    l00 = math.sqrt(s0)
    l10 = s1 / l00
    l11 = math.sqrt(s2 - l10 * l10)
    l20 = s2 / l00
    l21 = (s3 - l20 * l10) / l11
    l22 = math.sqrt(s4 - l20 * l20 - l21 * l21)
    l30 = s3 / l00
    l31 = (s4 - l30 * l10) / l11
    l32 = (s5 - l30 * l20 - l31 * l21) / l22
    l33 = math.sqrt(s6 - l30 * l30 - l31 * l31 - l32 * l32)
    z1 = 1.0 / l11  # L z = e₁ (z₀ = 0)
    z2 = -l21 * z1 / l22
    z3 = -(l31 * z1 + l32 * z2) / l33
    y3 = z3 / l33  # Lᵀ y = z
    y2 = (z2 - l32 * y3) / l22
    y1 = (z1 - l21 * y2 - l31 * y3) / l11
    y0 = -(l10 * y1 + l20 * y2 + l30 * y3) / l00
    slope = (y0 * r0 + y1 * r1 + y2 * r2 + y3 * r3) / scale
    # the straight line's slope variance is 1/Σ(τ - τ̄)²; the cubic's, its inverse's
    # element: the line is nested in the cubic, so the difference is the excess's
    centred = s2 - s1**2 / s0
    excess = (y1 - 1.0 / centred) / scale**2
    return slope, max(excess, 0.0)


@njit(cache=True)
def _take_window(t, x, i, lo, hi, v, duration, spread, with_spread, error, slope=np.nan):
    """Sample ``i``'s v, the time it is taken over and (``with_spread``) its spread,
    from the window [lo, hi] (``slope``: x's over it, where already known)."""
    v[i] = _slope(t, x, lo, hi) if math.isnan(slope) else slope
    duration[i] = t[hi] - t[lo]
    if with_spread and hi - lo >= CUBIC_SAMPLES - 1:
        # the counts' error moves the two slopes apart too; what they add is taken off
        # (the re-reading of the record holds it), the rest is the speed's change
        cubic, excess = _cubic_slope(t, x, i, lo, hi)
        spread[i] = math.sqrt(max((cubic - v[i]) ** 2 - error**2 * excess, 0.0))


__all__ = ["AGREEMENT", "CHOICE_ROWS", "CUBIC_SAMPLES", "FFT_WINDOW", "NOISE_TO_SIGNAL",
           "ORDER", "UNIFORM_TOLERANCE", "WINDOWS", "acceleration_at", "acceleration_bias",
           "acceleration_noise", "adaptive_windows", "choose_window", "curvature_fit",
           "local_fit", "smooth_fit"]
