"""``detection``: the rig notices break-away late while the force ramps."""

from __future__ import annotations

from ...quasistatic import e12_velocity
from ..residuals import correlation
from .base import BREAKAWAY_Z, Effect, Param, _needs_rates, _project


class Detection(Effect):
    name = "detection"
    kinds = ("breakaway",)
    off = {"tau_det": 0.0}
    params = (Param("tau_det", "s", lambda sc: (0.0, 100 * sc.force / sc.rate)),)
    description = "the rig notices motion a time τ_det late while the force keeps ramping"
    regressor = {"breakaway": "k"}

    def unavailable(self, pb):
        return _needs_rates(pb)

    def sensor(self, pb, p, F, ctx):
        return F + pb.k * p["tau_det"]

    def starts(self, pb, current, r):
        return [{"tau_det": max(_project(r, pb.k), 0.0)}]

    def signature(self, pb, r, params):
        return (f"the break-away force rises linearly with the rate k, against E13's fall "
                f"(r = {correlation(r, pb.k):.2f})")


def viscous_equivalent_of_detection(tau_det, s, F_hat):
    """σ that raises F_ba like a detection delay τ_det:
    ``σ·ẋ* = k·τ_det`` with ``ẋ* = k/(s·F̂·|ln z*|)`` gives ``σ = τ_det·s·F̂·|ln z*|``."""
    return tau_det / float(e12_velocity(1.0, F_hat, s, BREAKAWAY_Z))
