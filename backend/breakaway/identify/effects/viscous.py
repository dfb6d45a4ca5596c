"""``viscous``: σ·v added to the steady state."""

from __future__ import annotations

import numpy as np

from ..residuals import correlation
from .base import Effect, Param, sliding_unseen, _needs_rates, _project


class Viscous(Effect):
    name = "viscous"
    kinds = ("timeseries", "steady", "breakaway")
    off = {"sigma": 0.0}
    params = (Param("sigma", "N·s/m", lambda sc: (0.0, 100 * sc.force / sc.speed)),)
    description = "viscous friction σ·v added to the steady state"
    regressor = {"timeseries": "v", "steady": "v", "breakaway": "k"}

    def unavailable(self, pb):
        return _needs_rates(pb)

    def unresolved(self, pb, params):
        return sliding_unseen(pb, params)

    def target(self, pb, p, v):
        return p["sigma"] * v

    def starts(self, pb, current, r):
        v = pb.speed_at_breakaway(current) if pb.kind == "breakaway" else pb.v
        return [{"sigma": max(_project(r, v), 0.0)}]

    def signature(self, pb, r, params):
        sliding, v, d = pb.sliding_rows(), pb.regressor_speed(), pb.signed_direction()
        c = correlation(r[sliding] * d[sliding], np.abs(v[sliding]))
        what = "k" if pb.kind == "breakaway" else "|v| in sliding"
        return f"the residual grows with {what} in the direction of motion (r = {c:.2f})"
