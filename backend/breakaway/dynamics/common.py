"""Pieces the dynamic models share: the Stribeck magnitude g of (E2) and its slope in
compiled form (the integrator's models call them per step)."""

from __future__ import annotations

import math

from numba import njit


@njit(cache=True)
def _g(v, Fc, Fs, V, delta):
    """g(v) of (E2) for a scalar v, with its limits at v = 0 (Fs for δ > 0, Fc for δ < 0)."""
    av = abs(v)
    if av == 0.0:
        return Fs if delta > 0 else Fc
    return Fc + (Fs - Fc) * math.exp(-((av / V) ** delta))


@njit(cache=True)
def _g_branch(u, Fc, Fs, V, delta):
    """g of (E2) on a branch of motion, for u = d·v, the speed along the branch's
    direction d: g(|v|) while u >= 0. Past u = 0 (the reversal that ends the branch, seen
    only by the stages of a step that the reversal event cuts) (u/V)^δ is continued as
    an odd function for δ > 0, smoothly for δ = 1: with g(|v|)'s kink there, a step
    across the reversal was refused until it was thousands of times shorter than the
    branch's steps, and every reversal paid ten such refusals."""
    if u >= 0.0 or delta < 0:
        return _g(u, Fc, Fs, V, delta)
    return Fc + (Fs - Fc) * math.exp((-u / V) ** delta)


@njit(cache=True)
def _dg_dabs(v, Fc, Fs, V, delta):
    """dg/d|v| for a scalar v (0 at v = 0 for δ >= 1)."""
    av = abs(v)
    if av == 0.0:
        return 0.0
    r = (av / V) ** delta
    return -(Fs - Fc) * delta * r / av * math.exp(-r)


#: Event codes a model's ``jump`` returns (a bit mask): a change of sign of ẋ (a new
#: presliding branch), a break-away (the presliding fraction reaches z*), the start of
#: a stick phase (the first reversal after a break-away), and a change of sign of the
#: reference velocity ṙ (the friction compensation switches branch).
EVENT_REVERSAL, EVENT_BREAKAWAY, EVENT_STICK, EVENT_COMPENSATION = 1, 2, 4, 8
