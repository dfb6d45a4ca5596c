"""``offset``: a constant bias of the force sensor."""

from __future__ import annotations

import numpy as np

from .base import Effect, Param, _direction_means, _fmt, _needs_both_directions


#: Rows in gross sliding each direction needs before an offset can be told from the levels.
MIN_SLIDING_ROWS = 5


class Offset(Effect):
    name = "offset"
    kinds = ("timeseries", "steady")
    off = {"F_offset": 0.0}
    params = (Param("F_offset", "N", lambda sc: (-10 * sc.force, 10 * sc.force)),)
    description = "a constant bias of the force sensor"
    regressor = {"timeseries": "t", "steady": "v"}

    def unavailable(self, pb):
        return _needs_both_directions(pb)

    def unresolved(self, pb, params):
        """An offset is told from the friction levels by sliding both ways (the levels
        change sign with the direction, an offset does not); a record that slides one
        way only, or never, cannot tell them apart."""
        if pb.kind != "timeseries":
            return None
        positive, negative = pb.sliding_each_way(params)
        if min(positive, negative) < MIN_SLIDING_ROWS:
            return (f"the record slides {positive} rows positive and {negative} negative: "
                    f"an offset is told from the friction levels only by sliding both ways")
        return None

    def sensor(self, pb, p, F, ctx):
        return F + p["F_offset"]

    def starts(self, pb, current, r):
        return [{"F_offset": float(np.median(r))}]

    def signature(self, pb, r, params):
        mp, mn = _direction_means(pb, r)
        unit = pb.data.unit("N")
        return (f"the residual has the same sign in both directions: mean {_fmt(mp)} {unit} "
                f"moving positive, {_fmt(mn)} {unit} moving negative")
