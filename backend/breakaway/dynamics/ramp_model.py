"""The ramp experiment (E7) with the note's presliding model (E6'): its compiled
right-hand side, force, reversal guard and jump, break-away test, and its problem set-up.

    y = [x, v]; mem = [x_r, F_r, d]; p = [Fc, Fs, V, delta, sigma, s, m, k, z_ba]
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..params import check_fraction, check_positive, check_stribeck
from ..presliding import shape_scalar
from .common import EVENT_REVERSAL, _g_branch

_P_FC, _P_FS, _P_V, _P_DELTA, _P_SIGMA, _P_S, _P_M, _P_K, _P_ZBA = range(9)


@njit(cache=True)
def _presliding_force(t, y, p, mem):
    z = p[_P_S] * abs(y[0] - mem[0])
    shape = shape_scalar(z)
    g = _g_branch(mem[2] * y[1], p[_P_FC], p[_P_FS], p[_P_V], p[_P_DELTA])
    target = mem[2] * g + p[_P_SIGMA] * y[1]
    return mem[1] + (target - mem[1]) * shape


@njit(cache=True)
def _presliding_rhs(t, y, p, mem, dy):
    dy[0] = y[1]
    dy[1] = (p[_P_K] * t - _presliding_force(t, y, p, mem)) / p[_P_M]


@njit(cache=True)
def _presliding_guard(t, y, p, mem):
    return y[1] * mem[2]


@njit(cache=True)
def _presliding_jump(t, y, p, mem):
    # a change of sign of ẋ: new branch at the current x and F
    F = _presliding_force(t, y, p, mem)
    mem[0] = y[0]
    mem[1] = F
    mem[2] = -mem[2]
    return EVENT_REVERSAL


@njit(cache=True)
def _presliding_stop(t, y, p, mem):
    if mem[2] > 0:
        return p[_P_S] * abs(y[0] - mem[0]) - p[_P_ZBA]
    return -1.0



def _presliding_params(Fc, Fs, V, delta, s, sigma, m, z_ba):
    """The checked parameter vector ``p`` (rate k = 0)."""
    check_stribeck(Fc, Fs, V, delta, sigma)
    check_positive(s=s, m=m)
    check_fraction("z_ba", z_ba)
    return np.array([Fc, Fs, V, delta, sigma, s, m, 0.0, z_ba], dtype=float)


def _presliding_problem(ks, Fc, Fs, V, delta, s, sigma, m, z_ba, rtol):
    """Parameters, initial state, memory, time limits and tolerances per rate."""
    p = _presliding_params(Fc, Fs, V, delta, s, sigma, m, z_ba)
    y0 = np.zeros(2)
    mem0 = np.array([0.0, 0.0, 1.0])  # virgin state: x_r = 0, F_r = 0, d = +1
    # quasi-static time to reach the steady level, or the time the ramp alone needs
    # to push the mass across the presliding distance, whichever is longer
    t_end = 20.0 * (max(Fs, Fc) / ks + (6.0 * m / (s * ks)) ** (1.0 / 3.0))
    # absolute tolerances: x against 1/s, v against the E12 velocity k/(s·Fc)
    atols = 1e-3 * rtol * np.column_stack([np.full(ks.size, 1.0 / s), ks / (s * Fc)])
    return p, y0, mem0, t_end, atols


