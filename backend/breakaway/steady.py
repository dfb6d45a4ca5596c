"""Steady-state (Stribeck) friction, the note's (E2)."""

from __future__ import annotations

import numpy as np

from .params import check_stribeck


def stribeck_kernel(v, Fc, Fs, V, delta, log_speed=None):
    """g(v) of (E2) without argument checks, for fits that move the parameters.

    Same formula as :func:`stribeck_magnitude`; ``Fc`` and ``Fs`` may be arrays (per-row
    levels, e.g. separate levels per direction). Overflow gives the limits, not warnings.
    A fit that evaluates g at the same velocities many times may pass
    ``log_speed = log|v|`` (−inf at rest): ``(|v|/V)^δ = exp(δ·(log|v| − log V))`` then
    costs two exponentials instead of a power.
    """
    if log_speed is not None and delta > 0:
        with np.errstate(over="ignore"):
            return Fc + (Fs - Fc) * np.exp(-np.exp(delta * (log_speed - np.log(V))))
    v = np.abs(np.asanyarray(v, dtype=float))
    with np.errstate(divide="ignore", over="ignore"):
        # (|v|/V)^δ: at v = 0 this is 0 for δ > 0 and +inf for δ < 0, which gives the
        # documented limits g(0) = Fs and g(0) = Fc respectively.
        weight = np.exp(-np.power(v / V, delta))
    return Fc + (Fs - Fc) * weight


def stribeck_magnitude(v, Fc, Fs, V, delta):
    """Magnitude g(v) of the Stribeck curve (E2).

    ``g(v) = Fc + (Fs − Fc)·exp(−(|v|/V)^δ)``.

    Parameters
    ----------
    v : array_like
        Velocity [m/s].
    Fc, Fs : float
        Coulomb and Stribeck levels [N], ``0 < Fc <= Fs``.
    V : float
        Stribeck velocity [m/s], ``V > 0``.
    delta : float
        Shape exponent [-], non-zero. For ``δ < 0`` the curve rises from ``g(0) = Fc``
        (the limit) to ``Fs`` (velocity strengthening).

    Returns
    -------
    numpy.ndarray
        g(v) [N], same shape as ``v``.
    """
    check_stribeck(Fc, Fs, V, delta)
    return stribeck_kernel(v, Fc, Fs, V, delta)


def steady_state_force(v, Fc, Fs, V, delta, sigma=0.0):
    """Steady-state friction Fss(v) (E2).

    ``Fss(v) = sgn(v)·g(v) + σ·v``.

    Parameters
    ----------
    v : array_like
        Velocity [m/s].
    Fc, Fs, V, delta :
        See :func:`stribeck_magnitude`.
    sigma : float, optional
        Viscous coefficient [N s/m], ``σ >= 0``.

    Returns
    -------
    numpy.ndarray
        Fss(v) [N]; ``Fss(0) = 0``.
    """
    check_stribeck(Fc, Fs, V, delta, sigma)
    v = np.asanyarray(v, dtype=float)
    return np.sign(v) * stribeck_magnitude(v, Fc, Fs, V, delta) + sigma * v
