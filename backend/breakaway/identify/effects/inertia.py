"""``inertia``: an inertial force m_e·a in the measured force."""

from __future__ import annotations

import numpy as np

from ...quasistatic import e12_acceleration
from ..residuals import correlation
from .base import BREAKAWAY_Z, Effect, Param, _needs_rates, _project


class Inertia(Effect):
    name = "inertia"
    reads_acceleration = True
    kinds = ("timeseries", "breakaway")
    off = {"m_e": 0.0}
    params = (Param("m_e", "kg", lambda sc: (0.0, 100 * sc.force / sc.accel)),)
    description = "an inertial force m_e·a in the measured force"
    regressor = {"timeseries": "a", "breakaway": "k"}

    def unavailable(self, pb):
        return _needs_rates(pb)

    def unresolved(self, pb, params):
        if pb.kind != "timeseries" or pb.derivatives.acceleration_resolved:
            return None
        noise = pb.derivatives.acceleration_noise
        return (f"the record's accelerations are within what the resolution of x makes of "
                f"them (RMS {float(np.sqrt(np.mean(pb.a**2))):.3g} against "
                f"{noise:.3g} {pb.data.unit('m/s²')} from x's steps or noise alone): an "
                f"inertial force cannot be told from how a is read")

    def _acceleration(self, pb, F_hat):
        if pb.kind == "breakaway":
            return e12_acceleration(pb.k, F_hat, pb.s, BREAKAWAY_Z)
        return pb.a

    def sensor(self, pb, p, F, ctx):
        a = ctx["a"] if "a" in ctx else self._acceleration(pb, ctx.get("F_hat"))
        return F + p["m_e"] * a

    def acceleration_gain(self, pb, p) -> float:
        return p["m_e"]

    def starts(self, pb, current, r):
        F_hat = current["Fc"] + (current["Fs"] - current["Fc"]) / 2
        return [{"m_e": max(_project(r, self._acceleration(pb, F_hat)), 0.0)}]

    def signature(self, pb, r, params):
        if pb.kind == "breakaway":
            c = correlation(r, pb.k**2)
            return f"the residual grows with k² like an inertial term (r = {c:.2f})"
        return f"the residual follows the acceleration a = dv/dt (r = {correlation(r, pb.a):.2f})"
