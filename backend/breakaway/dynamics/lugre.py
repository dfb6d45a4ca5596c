"""The LuGre comparison model (Canudas de Wit et al. 1995) under the same
ramp: its compiled right-hand side and force, the first-maximum stop, and its problem
set-up.

    y = [x, v, z]; mem unused; p = [sigma0, sigma1, sigma2, Fc, Fs, vs, delta, m, k]
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..params import LUGRE_1995, _finite, check_positive, check_stribeck
from .common import _dg_dabs, _g

_L_S0, _L_S1, _L_S2, _L_FC, _L_FS, _L_VS, _L_DELTA, _L_M, _L_K = range(9)


@njit(cache=True)
def _lugre_zdot(y, p):
    g = _g(y[1], p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])
    return y[1] - p[_L_S0] * abs(y[1]) * y[2] / g


@njit(cache=True)
def _lugre_force(t, y, p, mem):
    return p[_L_S0] * y[2] + p[_L_S1] * _lugre_zdot(y, p) + p[_L_S2] * y[1]


@njit(cache=True)
def _lugre_rhs(t, y, p, mem, dy):
    dy[0] = y[1]
    dy[1] = (p[_L_K] * t - _lugre_force(t, y, p, mem)) / p[_L_M]
    dy[2] = _lugre_zdot(y, p)


@njit(cache=True)
def _lugre_guard(t, y, p, mem):
    return 1.0


@njit(cache=True)
def _lugre_jump(t, y, p, mem):
    return 0  # never called: the guard never crosses


@njit(cache=True)
def _lugre_stop(t, y, p, mem):
    """−dF/dt: its first crossing to >= 0 is the first local maximum of F."""
    v, zb = y[1], y[2]
    a = (p[_L_K] * t - _lugre_force(t, y, p, mem)) / p[_L_M]
    g = _g(v, p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])
    av = abs(v)
    zdot = v - p[_L_S0] * av * zb / g
    # d/dt (|v|/g(v)) = sgn(v)·a·(g − |v|·dg/d|v|)/g²
    ratio_dot = math.copysign(1.0, v) * a * (g - av * _dg_dabs(v, p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])) / (g * g)
    if av == 0.0:
        ratio_dot = abs(a) / g
    zddot = a - p[_L_S0] * (ratio_dot * zb + av / g * zdot)
    return -(p[_L_S0] * zdot + p[_L_S1] * zddot + p[_L_S2] * a)



def _lugre_params(params):
    """LUGRE_1995 with the checked overrides ``params``, and its vector ``p`` (k = 0)."""
    unknown = sorted(set(params or {}) - set(LUGRE_1995))
    if unknown:
        raise ValueError(f"unknown LuGre parameter(s) {unknown}; known: {sorted(LUGRE_1995)}")
    q = {**LUGRE_1995, **(params or {})}
    # the LuGre names first (vs, sigma2), then (E2)'s remaining constraints
    check_positive(vs=q["vs"], sigma0=q["sigma0"], m=q["m"])
    for name in ("sigma1", "sigma2"):
        if _finite(name, q[name]) < 0:
            raise ValueError(f"{name} must be >= 0, got {q[name]}")
    check_stribeck(q["Fc"], q["Fs"], q["vs"], q["delta"], q["sigma2"])
    p = np.array([q["sigma0"], q["sigma1"], q["sigma2"], q["Fc"], q["Fs"], q["vs"],
                  q["delta"], q["m"], 0.0])
    return q, p


def _lugre_problem(ks, params, rtol):
    q, p = _lugre_params(params)
    bristle = q["Fs"] / q["sigma0"]  # bristle deflection at stiction [m]
    s = 1.0 / bristle
    t_end = 20.0 * (q["Fs"] / ks + (6.0 * q["m"] / (s * ks)) ** (1.0 / 3.0))
    v_scale = np.maximum(ks / (s * q["Fc"]), q["vs"])
    atols = 1e-3 * rtol * np.column_stack([np.full(ks.size, bristle), v_scale,
                                           np.full(ks.size, bristle)])
    return p, np.zeros(3), np.zeros(1), t_end, atols


