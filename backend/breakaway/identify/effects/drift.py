"""``drift``: the friction level drifting in time (MODEL.md §7)."""

from __future__ import annotations

import numpy as np

from ..residuals import correlation
from .base import Effect, Param, _project


class Drift(Effect):
    name = "drift"
    kinds = ("timeseries",)
    params = (Param("alpha", "1/s", lambda sc: (-0.95 / sc.duration, 20.0 / sc.duration)),)
    description = "friction level drifting linearly in time (wear, temperature)"
    regressor = {"timeseries": "t"}

    def scale_g(self, pb, p, g):
        return g * (1.0 + p["alpha"] * (pb.t - pb.t[0]))

    def starts(self, pb, current, r):
        basis = (pb.t - pb.t[0]) * (pb.measured - r)
        lo, hi = self.params[0].bounds(pb.scales)
        return [{"alpha": float(np.clip(_project(r, basis), 0.9 * lo, 0.9 * hi))}]

    def signature(self, pb, r, params):
        sliding, d = pb.sliding_rows(), pb.signed_direction()
        c = correlation(r[sliding] * d[sliding], pb.t[sliding])
        return f"the sliding-level error changes steadily with time (r = {c:.2f} against t)"
