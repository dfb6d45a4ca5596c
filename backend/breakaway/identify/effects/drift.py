"""``drift``: the friction level drifting in time."""

from __future__ import annotations

import numpy as np
from scipy.stats import spearmanr

from ..residuals import correlation
from .base import Effect, Param, _project, sliding_unseen

#: Stretches of the record in time whose level error must follow the drift.
TIME_BLOCKS = 6
#: ... in rank (Spearman) at least this much ...
MONOTONE_RANK = 0.6
#: ... and in size within this factor of the drift's own rise.
SIZE_FACTOR = 3.0
#: Sliding rows a stretch needs in a direction to count.
MIN_STRETCH_ROWS = 5


class Drift(Effect):
    name = "drift"
    kinds = ("timeseries",)
    off = {"alpha": 0.0}
    params = (Param("alpha", "1/s", lambda sc: (-0.95 / sc.duration, 20.0 / sc.duration)),)
    description = "friction level drifting linearly in time (wear, temperature)"
    regressor = {"timeseries": "t"}
    acts_through = "t"

    def unresolved(self, pb, params):
        """A drift is one monotone trend of the sliding level, the same in both
        directions: in each direction, the level error of :data:`TIME_BLOCKS` stretches of
        the record (what the drift took and what is left) must follow the drift's own
        rise in rank (:data:`MONOTONE_RANK`) and in size (within :data:`SIZE_FACTOR`).
        A dependence on time that is not that (a machine warming and cooling, a
        position dependence met at other times) is not a drift. A record that never
        reaches gross sliding does not show the level it scales."""
        unseen = sliding_unseen(pb, params)
        if unseen:
            return unseen
        without = pb.predict({**params, "alpha": 0.0})
        own = pb.measured - without  # what the drift took, and what is left
        added = pb.predict(params) - without  # the drift's own force
        sliding, d = pb.sliding_rows(), pb.signed_direction()
        t = pb.t
        stretch = np.minimum((TIME_BLOCKS * (t - t[0]) / max(t[-1] - t[0], 1e-300)).astype(int),
                             TIME_BLOCKS - 1)
        for way, name in ((1, "positive"), (-1, "negative")):
            rows = sliding & (d == way)
            found = [(float(np.mean(d[sel] * own[sel])), float(np.mean(d[sel] * added[sel])))
                     for sel in (rows & (stretch == b) for b in range(TIME_BLOCKS))
                     if np.count_nonzero(sel) >= MIN_STRETCH_ROWS]
            if len(found) < 3:
                continue
            level, expected = np.array(found).T
            rank = spearmanr(level, expected).statistic
            spread = float(np.var(expected))
            size = float(np.cov(level, expected, bias=True)[0, 1]) / spread if spread > 0 else 0.0
            if not (rank >= MONOTONE_RANK and 1 / SIZE_FACTOR <= size <= SIZE_FACTOR):
                return (f"the sliding level moving {name} does not follow one monotone trend "
                        f"in time (rank correlation {rank:.2f} with the drift's rise over "
                        f"{len(found)} stretches, {size:.2g} of its size): a dependence on "
                        f"time that is not a drift")
        return None

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
