"""``lag``: frictional lag, g at a filtered velocity."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..residuals import correlation
from .base import Effect, Param, sliding_unseen


@njit(cache=True)
def lag_filter(v, t, tau):
    """First-order lag of v: ``v_f,i = v_f,i−1 + (1 − exp(−Δt_i/τ))·(v_i − v_f,i−1)``."""
    n = v.size
    out = np.empty(n)
    out[0] = v[0]
    for i in range(1, n):
        w = 1.0 - math.exp(-(t[i] - t[i - 1]) / tau) if tau > 0.0 else 1.0
        out[i] = out[i - 1] + w * (v[i] - out[i - 1])
    return out


#: A lag's gain per row in presliding (z < 1) may be at most this many times its gain
#: per row in sliding (a true lag's: 4-6 on strokes whose presliding it shapes too).
MAX_PRESLIDING_CROWDING = 15.0


class Lag(Effect):
    name = "lag"
    kinds = ("timeseries",)
    off = {"tau": 0.0}
    params = (Param("tau", "s", lambda sc: (0.0, sc.duration / 4)),)
    description = "frictional lag: the Stribeck level follows a filtered velocity"
    regressor = {"timeseries": "v"}
    acts_through = "time since reversal"

    def unresolved(self, pb, params):
        unseen = sliding_unseen(pb, params)
        if unseen:
            return unseen  # the lag delays g, which a record that never slides never shows
        span = pb.derivatives.velocity_span
        if params["tau"] <= span:
            return (f"a lag of {params['tau']:.3g} s is no longer than the time v is taken over "
                    f"({span:.3g} s): it cannot be told from how the velocity is measured")
        # frictional lag acts in sliding and in presliding alike; a gain crowded into the
        # rows right after reversals, where the presliding shape decides, is that
        # shape's misfit
        r_lag = pb.measured - pb.predict(params)
        r_none = pb.measured - pb.predict({**params, "tau": 0.0})
        gain = r_none**2 - r_lag**2
        presliding = pb.presliding_fraction(params) < 1.0
        if presliding.all() or not presliding.any():
            return None
        inside = float(np.mean(gain[presliding]))
        outside = float(np.mean(gain[~presliding]))
        if inside > MAX_PRESLIDING_CROWDING * max(outside, 0.0):
            ratio = inside / outside if outside > 0 else math.inf
            return (f"its gain per row right after reversals, where the shape of presliding "
                    f"decides, is {ratio:.3g} times that in sliding: it stands in for that "
                    f"shape, not for a lag of friction")
        return None

    def slip_velocity(self, pb, p, v):
        return lag_filter(v, pb.t, p["tau"])

    def starts(self, pb, current, r):
        char_time = pb.scales.speed / pb.scales.accel
        return [{"tau": float(tau)} for tau in char_time * np.array([0.003, 0.01, 0.03, 0.1, 0.3])]

    def signature(self, pb, r, params):
        sliding, d = pb.sliding_rows(), pb.signed_direction()
        c = correlation(r[sliding] * d[sliding], pb.a[sliding] * d[sliding])
        return (f"in sliding the error depends on whether the speed rises or falls "
                f"(r = {c:.2f} against the acceleration along the motion): F–v loops open")
