"""Quasi-static break-away: the phase family (E12) and the break-away curve (E13).

Neglecting inertia in presliding, ``dF/dt = k`` with ``F = F̂·f(z)`` gives

    ẋ(z) = −k / (s·F̂·ln z),   0 < z < 1                                   (E12)

and the break-away force ``F_ba(k) = Fss(ẋ(z*))`` (E13). ``F̂`` is ``Fc``, ``Fs``,
``avg = Fc + (Fs − Fc)/2`` (the note's choices) or ``self``: the smallest positive root
of ``ẋ·Fss(ẋ) = −k/(s·ln z)``.
"""

from __future__ import annotations

import numpy as np

from .params import FIG3_RATES, check_f_hat, check_fraction, check_positive, check_stribeck
from .steady import steady_state_force

#: Grid points used to bracket the smallest root when ẋ·Fss(ẋ) may turn back.
_SELF_BRACKET_POINTS = 48
_SELF_BISECTIONS = 40
#: Safeguarded Newton steps where ẋ·Fss(ẋ) is strictly increasing (converges in ~6).
_SELF_NEWTON_STEPS = 30
#: ln y beyond which y = (v/V)^δ is not formed (it would overflow; e^(−y) is 0 anyway).
_LOG_Y_MAX = 700.0


def level(F_hat, Fc, Fs):
    """The constant ``F̂`` [N] for ``Fc``, ``Fs`` or ``avg`` (``self`` has none)."""
    check_f_hat(F_hat)
    if F_hat == "self":
        raise ValueError("F_hat 'self' has no constant level")
    return {"Fc": Fc, "Fs": Fs, "avg": Fc + (Fs - Fc) / 2}[F_hat]


def e12_velocity(k, F_hat, s=1.0, z=0.95):
    """ẋ(z) of (E12) for a constant level ``F̂`` [m/s], without argument checks.

    ``ẋ = −k/(s·F̂·ln z)``; ``k`` [N/s] and ``F̂`` [N] may be arrays (per-row levels in
    fits), ``s`` [1/m], ``0 < z < 1``.
    """
    return np.asanyarray(k, dtype=float) / (s * F_hat * -np.log(z))


def e12_acceleration(k, F_hat, s=1.0, z=0.95):
    """ẍ at ``z`` along the quasi-static branch (E12) [m/s²], without argument checks.

    Differentiating (E12) with ``dz/dt = s·ẋ`` gives ``ẍ = k²/(s·F̂²·z·|ln z|³)``: the
    acceleration that an inertial term m·ẍ meets at break-away.
    """
    k = np.asanyarray(k, dtype=float)
    return k**2 / (s * F_hat**2 * z * (-np.log(z)) ** 3)


def _work_and_slope(v, Fc, Fs, V, delta, sigma):
    """``h(v) = v·Fss(v)`` and ``h'(v)`` for ``v > 0`` (parameters already checked).

    ``h' = g − (Fs − Fc)·δ·y·e^(−y) + 2σv`` with ``y = (v/V)^δ``. ``y`` is formed from its
    logarithm and ``y·e^(−y)`` as ``exp(ln y − y)``: with a large ``|δ|`` (δ = 1000) ``y``
    overflows a float where ``e^(−y)`` and ``y·e^(−y)`` are long 0, and ``0·inf`` is NaN.
    """
    log_y = delta * (np.log(v) - np.log(V))
    # e^(−y) is 0 from y ≈ 745 on: capping ln y at 700 changes no value
    y = np.exp(np.minimum(log_y, _LOG_Y_MAX))
    decay = (Fs - Fc) * np.exp(-y)
    g = Fc + decay
    return v * g + sigma * v * v, g - (Fs - Fc) * delta * np.exp(log_y - y) + 2 * sigma * v


def _work_is_increasing(Fc, Fs, delta, sigma):
    """Whether ``h(v) = v·Fss(v)`` is strictly increasing for ``v > 0``.

    ``h' = Fc + (Fs − Fc)·e^(−y)·(1 − δ·y) + 2σv`` with ``y = (v/V)^δ``. For ``δ < 0`` every
    term is positive; for ``δ > 0`` the minimum of ``e^(−y)·(1 − δy)`` is
    ``−δ·e^(−1−1/δ)`` (at ``y = 1 + 1/δ``), so ``Fc > (Fs − Fc)·δ·e^(−1−1/δ)`` suffices.
    """
    return delta < 0 or Fc > (Fs - Fc) * delta * np.exp(-1.0 - 1.0 / delta)


def _self_consistent_velocity(c, Fc, Fs, V, delta, sigma):
    """Smallest positive root ẋ of ``ẋ·Fss(ẋ) = c`` for each ``c > 0`` (vectorised).

    ``ẋ·Fss(ẋ)`` lies between ``min(Fc, Fs)·ẋ`` and ``max(Fc, Fs)·ẋ + σ·ẋ²``, which brackets
    every root. Where ``ẋ·Fss(ẋ)`` is strictly increasing (:func:`_work_is_increasing`,
    the usual case) the root is unique and Newton steps kept inside the bracket find it;
    otherwise a grid over the bracket finds the first sign change and bisection refines it.
    """
    c = np.asanyarray(c, dtype=float)
    g_lo, g_hi = min(Fc, Fs), max(Fc, Fs)
    if sigma > 0:
        lo = 2 * c / (g_hi + np.sqrt(g_hi**2 + 4 * sigma * c))  # root of g_hi·v + σ·v² = c
    else:
        lo = c / g_hi
    hi = c / g_lo
    if _work_is_increasing(Fc, Fs, delta, sigma):
        return _bracketed_newton(c, lo, hi, Fc, Fs, V, delta, sigma)
    grid = np.linspace(0.0, 1.0, _SELF_BRACKET_POINTS)
    v = lo[..., None] + (hi - lo)[..., None] * grid
    excess = _work_and_slope(np.maximum(v, 1e-300), Fc, Fs, V, delta, sigma)[0] - c[..., None]
    # first grid point at or above the target; the bracket's top is, up to round-off
    excess[..., -1] = np.maximum(excess[..., -1], 0.0)
    first = np.argmax(excess >= 0, axis=-1)
    first = np.maximum(first, 1)
    a = np.take_along_axis(v, (first - 1)[..., None], axis=-1)[..., 0]
    b = np.take_along_axis(v, first[..., None], axis=-1)[..., 0]
    for _ in range(_SELF_BISECTIONS):
        mid = 0.5 * (a + b)
        above = _work_and_slope(mid, Fc, Fs, V, delta, sigma)[0] >= c
        b = np.where(above, mid, b)
        a = np.where(above, a, mid)
    return 0.5 * (a + b)


def _bracketed_newton(c, lo, hi, Fc, Fs, V, delta, sigma):
    """Root of an increasing ``h(v) − c`` in ``[lo, hi]``: Newton, bisecting when a step
    would leave the bracket, which shrinks every step."""
    lo, hi = lo.copy(), hi.copy()
    v = 0.5 * (lo + hi)
    for _ in range(_SELF_NEWTON_STEPS):
        h, slope = _work_and_slope(v, Fc, Fs, V, delta, sigma)
        above = h >= c
        hi = np.where(above, v, hi)
        lo = np.where(above, lo, v)
        step = v - (h - c) / slope
        # closed bounds: a converged v sits on the bracket's edge and steps onto itself
        inside = (step >= lo) & (step <= hi)
        new = np.where(inside, step, 0.5 * (lo + hi))
        if np.all(np.abs(new - v) <= 1e-14 * v):
            return new
        v = new
    return v


def presliding_velocity(z, k, Fc, Fs, V, delta, s=1.0, sigma=0.0, F_hat="avg"):
    """Relative velocity in presliding as a function of z (E12).

    Parameters
    ----------
    z : array_like
        Normalised presliding distance [-], ``0 <= z < 1``; ``ẋ(0) = 0``.
    k : array_like
        Actuation force rate [N/s], ``k > 0``; broadcast against ``z``.
    Fc, Fs, V, delta, sigma :
        Steady-state parameters (E2).
    s : float, optional
        Presliding scale [1/m].
    F_hat : {'Fc', 'Fs', 'avg', 'self'}, optional
        Steady-state level used for ``F̂``.

    Returns
    -------
    numpy.ndarray
        ẋ [m/s], broadcast shape of ``z`` and ``k``.
    """
    check_stribeck(Fc, Fs, V, delta, sigma)
    check_positive(s=s)
    check_f_hat(F_hat)
    z = np.asanyarray(z, dtype=float)
    k = np.asanyarray(k, dtype=float)
    if np.any(~np.isfinite(k)) or np.any(k <= 0):
        raise ValueError("k must be finite and > 0")
    if np.any(~np.isfinite(z)) or np.any((z < 0) | (z >= 1)):
        raise ValueError("z must be in [0, 1)")
    with np.errstate(divide="ignore"):
        # c = −k/(s·ln z) = ẋ·F̂ ; c = 0 at z = 0
        c = np.where(z > 0, k / (s * -np.log(np.where(z > 0, z, 0.5))), 0.0)
    if F_hat != "self":
        return c / level(F_hat, Fc, Fs)
    c, shape = np.broadcast_arrays(c, np.empty(np.broadcast_shapes(c.shape, k.shape)))
    c = np.array(c, dtype=float)
    out = np.zeros(c.shape)
    positive = c > 0
    out[positive] = _self_consistent_velocity(c[positive], Fc, Fs, V, delta, sigma)
    return out


def phase_family(Fc, Fs, V, delta, s=1.0, sigma=0.0, F_hat="avg", k=FIG3_RATES,
                 n=200, z_max=0.99):
    """The (z, ẋ) phase diagrams of the note's Fig. 3 (E12).

    Parameters
    ----------
    Fc, Fs, V, delta, s, sigma, F_hat :
        See :func:`presliding_velocity`.
    k : array_like, optional
        Rates [N/s]; the note's Fig. 3 family by default.
    n : int, optional
        Points per curve, ``z`` uniform on ``[0, z_max]``.
    z_max : float, optional
        Last z [-]; ẋ grows without bound as ``z → 1``.

    Returns
    -------
    z : numpy.ndarray, shape (n,)
    v : numpy.ndarray, shape (len(k), n)
        ẋ [m/s] for each rate.
    """
    check_fraction("z_max", z_max)
    z = np.linspace(0.0, z_max, int(n))
    k = np.atleast_1d(np.asanyarray(k, dtype=float))
    return z, presliding_velocity(z[None, :], k[:, None], Fc, Fs, V, delta, s, sigma, F_hat)


def breakaway_force(k, Fc, Fs, V, delta, s=1.0, sigma=0.0, F_hat="avg", z_ba=0.95):
    """Quasi-static break-away force ``F_ba(k) = Fss(ẋ(z*))`` (E13).

    Parameters
    ----------
    k : array_like
        Actuation force rate [N/s], ``k > 0``.
    Fc, Fs, V, delta, s, sigma, F_hat :
        See :func:`presliding_velocity`.
    z_ba : float, optional
        Presliding fraction ``z*`` taken as break-away [-], ``0 < z* < 1``.

    Returns
    -------
    numpy.ndarray
        F_ba [N], same shape as ``k``. Depends on ``V`` and ``s`` only through ``s·V``.
    """
    check_fraction("z_ba", z_ba)
    velocity = presliding_velocity(z_ba, k, Fc, Fs, V, delta, s, sigma, F_hat)
    return steady_state_force(velocity, Fc, Fs, V, delta, sigma)


def breakaway_velocity(k, Fc, Fs, V, delta, s=1.0, sigma=0.0, F_hat="avg", z_ba=0.95):
    """ẋ at break-away, ``ẋ(z*)`` of (E12) [m/s]."""
    check_fraction("z_ba", z_ba)
    return presliding_velocity(z_ba, k, Fc, Fs, V, delta, s, sigma, F_hat)
