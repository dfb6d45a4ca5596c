"""``offset``: a constant bias of the force sensor (MODEL.md §7)."""

from __future__ import annotations

import numpy as np

from .base import Effect, Param, _direction_means, _fmt, _needs_both_directions


class Offset(Effect):
    name = "offset"
    kinds = ("timeseries", "steady")
    params = (Param("F_offset", "N", lambda sc: (-10 * sc.force, 10 * sc.force)),)
    description = "a constant bias of the force sensor"
    regressor = {"timeseries": "t", "steady": "v"}

    def unavailable(self, pb):
        return _needs_both_directions(pb)

    def sensor(self, pb, p, F, ctx):
        return F + p["F_offset"]

    def starts(self, pb, current, r):
        return [{"F_offset": float(np.median(r))}]

    def signature(self, pb, r, params):
        mp, mn = _direction_means(pb, r)
        return (f"the residual has the same sign in both directions: mean {_fmt(mp)} N "
                f"moving positive, {_fmt(mn)} N moving negative")
