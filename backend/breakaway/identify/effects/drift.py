"""``drift``: the friction level drifting in time."""

from __future__ import annotations

import numpy as np
from scipy.stats import spearmanr

from ..allowance import hat_functions
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
#: The stretches and a dependence on x are told apart when no singular value of their
#: column-scaled design falls below this share of the largest.
SEPARABLE = 1e-3


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
            kept = [b for b in range(TIME_BLOCKS)
                    if np.count_nonzero(rows & (stretch == b)) >= MIN_STRETCH_ROWS]
            if len(kept) < 3:
                continue
            rows &= np.isin(stretch, kept)
            expected = np.array([float(np.mean(d[sel] * added[sel]))
                                 for sel in (rows & (stretch == b) for b in kept)])
            # each stretch's level as it stands, and with a smooth dependence on x fitted
            # beside it: a stretch that met other parts of the travel (a position
            # dependence larger than the drift) does not break the trend where the
            # strokes cover the travel again and again
            trends = [_follows(level, expected) for level in
                      _stretch_levels(d[rows] * own[rows], stretch[rows], kept, pb.x[rows])]
            if not any(trend[0] for trend in trends):
                _, rank, size = trends[0]
                return (f"the sliding level moving {name} does not follow one monotone trend "
                        f"in time (rank correlation {rank:.2f} with the drift's rise over "
                        f"{len(kept)} stretches, {size:.2g} of its size): a dependence on "
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


def _stretch_levels(level, stretch, kept, x):
    """Each kept stretch's mean ``level``, and its level with piecewise-linear hat
    functions of ``x`` fitted beside the stretches (None where they cannot be told
    apart: x moving with time, as in a one-direction run)."""
    indicators = np.column_stack([stretch == b for b in kept]).astype(float)
    plain = level @ indicators / indicators.sum(axis=0)
    hats = hat_functions(x)[:, 1:]  # the hats sum to 1, as the indicators do
    design = np.column_stack([indicators, hats])
    norms = np.sqrt(np.sum(design * design, axis=0))
    norms[norms == 0] = 1.0
    coef, _, rank, _ = np.linalg.lstsq(design / norms, level, rcond=SEPARABLE)
    separable = rank == design.shape[1]
    return [plain] + ([coef[:len(kept)] / norms[:len(kept)]] if separable else [])


def _follows(level, expected):
    """Whether stretch levels follow the drift's own rise in rank and size, with the
    rank correlation and the size."""
    rank = spearmanr(level, expected).statistic
    spread = float(np.var(expected))
    size = float(np.cov(level, expected, bias=True)[0, 1]) / spread if spread > 0 else 0.0
    return rank >= MONOTONE_RANK and 1 / SIZE_FACTOR <= size <= SIZE_FACTOR, rank, size

