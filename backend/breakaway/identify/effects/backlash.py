"""``backlash``: a play between the measured point and the sliding body."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ...presliding import shape_scalar
from .base import Effect, Param, _fmt


@njit(cache=True)
def play_operator(x, play):
    """Body position behind a play of width ``play``.

    ``x_c,i = min(max(x_c,i−1, x_i − b/2), x_i + b/2)``, ``x_c,0 = x_0``. Returns the
    body position and whether the body is engaged (at the edge of the play).
    """
    n = x.size
    xc = np.empty(n)
    engaged = np.zeros(n, dtype=np.bool_)
    half = 0.5 * play
    xc[0] = x[0]
    engaged[0] = play == 0.0
    for i in range(1, n):
        lo = x[i] - half
        hi = x[i] + half
        c = xc[i - 1]
        if c <= lo:
            xc[i] = lo
            engaged[i] = True
        elif c >= hi:
            xc[i] = hi
            engaged[i] = True
        else:
            xc[i] = c
            engaged[i] = play == 0.0
    return xc, engaged


@njit(cache=True)
def engaged_presliding(xc, d, target, s, F_r0, engaged):
    """(E6') on the body position with the play's re-engagements.

    Each re-engagement starts a branch with ``x_r = x_c,i−1`` and ``F_r = 0``; the
    measured force is the friction while engaged and 0 while free.
    """
    n = xc.size
    friction = np.empty(n)
    out = np.empty(n)
    x_r = xc[0]
    F_r = F_r0
    for i in range(n):
        if i > 0:
            if engaged[i] and not engaged[i - 1]:
                x_r = xc[i - 1]
                F_r = 0.0
            elif d[i] != d[i - 1]:
                x_r = xc[i - 1]
                F_r = friction[i - 1]
        friction[i] = F_r + (target[i] - F_r) * shape_scalar(s * abs(xc[i] - x_r))
        out[i] = friction[i] if engaged[i] else 0.0
    return out


class Backlash(Effect):
    name = "backlash"
    kinds = ("timeseries",)
    off = {"play": 0.0}
    params = (Param("play", "m", lambda sc: (0.0, sc.travel / 2), profiled=True),)
    description = "a play of width b between the measured point and the sliding body"
    regressor = {"timeseries": "x"}
    acts_through = "x - x_r"

    def unavailable(self, pb):
        if pb.reversals < 2:
            return f"the record has {pb.reversals} reversal(s); a play shows at reversals"
        return None

    def unresolved(self, pb, params):
        if params["play"] <= pb.hysteresis:
            return (f"a play of {params['play']:.3g} is within the resolution of x (direction "
                    f"changes up to {pb.hysteresis:.3g} are not reversals): it cannot be told "
                    f"from how the record reads a turn")
        return None

    def body_motion(self, pb, p, ctx):
        if p["play"] <= 0:
            return ctx
        xc, engaged = play_operator(ctx["x"], p["play"])
        v = pb.body_velocity(xc, engaged) if ctx["x"] is pb.x else pb.kinematic_velocity(xc)
        return {**ctx, "x": xc, "v": v, "d": pb.kinematic_direction(xc), "engaged": engaged}

    def starts(self, pb, current, r):
        travel = pb.scales.travel
        presliding = 1.0 / current["s"]
        plays = np.concatenate([travel * np.array([0.003, 0.01, 0.03, 0.1]),
                                presliding * np.array([0.3, 1.0, 3.0])])
        plays = plays[plays < travel / 2]
        return [{"play": float(b)} for b in plays]

    def signature(self, pb, r, params):
        after = pb.after_reversal(max(2.0 / params.get("s", math.inf), params.get("play", 0.0) * 1.5))
        if after.any() and (~after).any():
            inside = math.sqrt(float(np.mean(r[after] ** 2)))
            outside = math.sqrt(float(np.mean(r[~after] ** 2)))
            unit = pb.data.unit("N")
            return (f"the residual concentrates right after reversals: RMS {_fmt(inside)} {unit} "
                    f"in the first part of each new stroke against {_fmt(outside)} {unit} "
                    f"elsewhere")
        return "the residual concentrates right after reversals"
