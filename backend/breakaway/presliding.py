"""Presliding friction with reversal memory: the shape (E4) and the law (E6').

Along a sampled trajectory the state is the current direction ``d``, and the position
``x_r`` and force ``F_r`` at the last motion reversal. Memory is local:
only the last reversal is kept.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .params import _finite, check_positive, check_stribeck
from .steady import stribeck_magnitude


def presliding_shape(z):
    """Presliding shape ``f(z) = z·(1 − ln z)`` (E4).

    Parameters
    ----------
    z : array_like
        Normalised presliding distance ``s·|x − x_r|`` [-], ``z >= 0``.

    Returns
    -------
    numpy.ndarray
        f(z) [-]: ``f(0) = 0``, ``f(1) = 1``, and ``f = 1`` for ``z >= 1``.
    """
    z = np.asanyarray(z, dtype=float)
    if np.any(z < 0):
        raise ValueError("z must be >= 0")
    zc = np.clip(z, 0.0, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        shape = zc * (1.0 - np.log(zc))
    return np.where(zc > 0, shape, 0.0)


def presliding_slope(z):
    """Derivative ``f'(z) = −ln z`` of (E4) [-]: infinite at 0, zero for ``z >= 1``."""
    z = np.asanyarray(z, dtype=float)
    if np.any(z < 0):
        raise ValueError("z must be >= 0")
    with np.errstate(divide="ignore"):
        return -np.log(np.clip(z, 0.0, 1.0))


def motion_direction(x):
    """Direction ``d_i`` of each sample of a position record.

    ``d_i = sgn(x_i − x_{i−1})`` where that is non-zero, else ``d_{i−1}``; ``d_0`` is the
    sign of the first non-zero increment (+1 if there is none).

    Parameters
    ----------
    x : array_like
        Position samples [m], 1-D.

    Returns
    -------
    numpy.ndarray
        ``d`` as float array of ±1, same length as ``x``.
    """
    x = np.asanyarray(x, dtype=float)
    step = np.sign(np.diff(x))
    moving = np.flatnonzero(step)
    if moving.size == 0:
        return np.ones_like(x)
    # forward fill the last non-zero increment sign; sample i uses increment i-1
    last = np.maximum.accumulate(np.where(step != 0, np.arange(step.size), -1))
    d = np.empty_like(x)
    d[0] = step[moving[0]]
    d[1:] = np.where(last >= 0, step[np.maximum(last, 0)], step[moving[0]])
    return d


@njit(cache=True)
def shape_scalar(z):
    """f(z) of (E4) for one ``z >= 0`` in compiled loops: 0 at 0, 1 from z = 1 on."""
    if z >= 1.0:
        return 1.0
    if z > 0.0:
        return z * (1.0 - np.log(z))
    return 0.0


@njit(cache=True)
def _presliding_kernel(x, d, target, s, F_r0):
    """Run (E6') sample by sample: ``F = F_r + (target − F_r)·f(z)``.

    ``target_i = d_i·g(v_i) + σ·v_i`` is precomputed (vectorised) by the caller.
    """
    n = x.size
    F = np.empty(n)
    x_r = x[0]
    F_r = F_r0
    for i in range(n):
        if i > 0 and d[i] != d[i - 1]:
            x_r = x[i - 1]
            F_r = F[i - 1]
        z = s * abs(x[i] - x_r)
        shape = shape_scalar(z)
        F[i] = F_r + (target[i] - F_r) * shape
    return F


def presliding_force_from_target(x, target, s, F0=0.0, direction=None):
    """(E6') along ``x`` for a given steady target ``d·g + σ·v`` per sample [N].

    The building block that effects (asymmetric levels, lag, drift) reuse: they change
    the target, not the reversal memory.
    """
    check_positive(s=s)
    F0 = _finite("F0", F0)
    x = np.asanyarray(x, dtype=float)
    d = motion_direction(x) if direction is None else np.asanyarray(direction, dtype=float)
    target = np.asanyarray(target, dtype=float)
    return _presliding_kernel(x, d, target, float(s), F0)


def presliding_force(t, x, Fc, Fs, V, delta, s, sigma=0.0, F0=0.0):
    """Friction along a sampled trajectory with reversal memory (E6').

    ``F = F_r + (d·g(v) + σ·v − F_r)·f(z)``, ``z = min(s·|x − x_r|, 1)``, with the
    reference discretisation of a sampled record: ``v = gradient(x, t)``, a reversal at
    sample ``i`` when ``d_i ≠ d_{i−1}`` sets ``x_r = x_{i−1}``, ``F_r = F_{i−1}``.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    x : array_like
        Positions [m] (taken as exact).
    Fc, Fs, V, delta, sigma :
        Steady-state parameters of (E2), units as in :func:`~breakaway.steady.steady_state_force`.
    s : float
        Presliding scale [1/m]; ``1/s`` is the presliding distance.
    F0 : float, optional
        Friction at the start [N] (``F_r`` of the initial branch); 0 is the virgin state.

    Returns
    -------
    numpy.ndarray
        Friction force F [N] at each sample.
    """
    check_stribeck(Fc, Fs, V, delta, sigma)
    check_positive(s=s)
    F0 = _finite("F0", F0)
    t = np.asanyarray(t, dtype=float)
    x = np.asanyarray(x, dtype=float)
    v = np.gradient(x, t)
    d = motion_direction(x)
    target = d * stribeck_magnitude(v, Fc, Fs, V, delta) + sigma * v
    return _presliding_kernel(x, d, target, float(s), float(F0))


#: Turning points of the default loop excitation, in units of the amplitude: the
#: virgin curve, the major loop, then a minor loop nested inside it (the note's Fig. 1).
LOOP_TURNING_POINTS = (0.0, 1.0, -1.0, 1.0, 0.2, 0.6, 0.2, 1.0, -1.0)


def hysteresis_loop(Fc, Fs, V, delta, s, sigma=0.0, amplitude=1.5, n=2000,
                    turning_points=LOOP_TURNING_POINTS, peak_speed=None):
    """Friction–displacement loop under a displacement excitation (the note's Fig. 1).

    The excitation passes through ``turning_points × amplitude / s`` with a half-cosine
    between consecutive points (zero velocity at each reversal).

    Parameters
    ----------
    Fc, Fs, V, delta, s, sigma :
        Model parameters (E2, E6').
    amplitude : float, optional
        Excitation amplitude in units of the presliding distance ``1/s`` [-]. Below 1
        the loop stays in presliding; above 1 it reaches gross sliding.
    n : int, optional
        Number of samples.
    turning_points : sequence of float, optional
        Reversal positions in units of the amplitude; the first is the start.
    peak_speed : float, optional
        Peak speed on each segment [m/s]; default ``0.1·V`` (``|V|`` for δ < 0).

    Returns
    -------
    x, F : numpy.ndarray
        Displacement [m] and friction [N].
    """
    check_stribeck(Fc, Fs, V, delta, sigma)  # before V is used for the default peak speed
    check_positive(amplitude=amplitude, s=s)
    if n < 10:
        raise ValueError(f"n must be >= 10, got {n}")
    points = np.asarray(turning_points, dtype=float) * amplitude / s
    phase = np.linspace(0.0, points.size - 1, n)
    segment = np.minimum(phase.astype(int), points.size - 2)
    frac = phase - segment
    start, stop = points[segment], points[segment + 1]
    x = start + (stop - start) * 0.5 * (1.0 - np.cos(np.pi * frac))
    # each segment lasts T so that its peak speed (π/2)·|Δx|/T equals peak_speed
    speed = 0.1 * V if peak_speed is None else float(peak_speed)
    check_positive(peak_speed=speed)
    durations = np.pi / 2 * np.abs(np.diff(points)) / speed
    durations = np.where(durations > 0, durations, 1.0)
    t = np.concatenate(([0.0], np.cumsum(durations)))[segment] + frac * durations[segment]
    # equal phase steps can coincide at segment joints only if n is tiny; keep t strictly increasing
    t = t + np.arange(n) * 1e-12
    return x, presliding_force(t, x, Fc, Fs, V, delta, s, sigma)
