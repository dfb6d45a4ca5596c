"""``dwell``: stiction rising with the dwell time."""

from __future__ import annotations

import numpy as np

from ..residuals import correlation
from .base import Effect, Param


class Dwell(Effect):
    name = "dwell"
    kinds = ("breakaway",)
    off = {"zeta": 0.0}
    params = (Param("zeta", "", lambda sc: (0.0, 100.0)),
              Param("tau_d", "s", lambda sc: (1e-4 * max(sc.dwell, 1e-6), 1e3 * max(sc.dwell, 1e-6)),
                    log=True))
    description = "stiction rising with the dwell time before the ramp"
    regressor = {"breakaway": "dwell"}

    def unavailable(self, pb):
        if "dwell" not in pb.data.columns:
            return "the file has no dwell column"
        distinct = np.unique(pb.dwell).size
        if distinct < 2:
            return "every row has the same dwell time, which only rescales Fs"
        if pb.level_only:
            return "single-rate: the Stribeck gap Fs − Fc that dwell scales is not determined"
        return None

    def levels(self, pb, p, Fc, Fs, negative):
        return Fc, Fc + (Fs - Fc) * (1.0 + p["zeta"] * np.log1p(pb.dwell / p["tau_d"]))

    def starts(self, pb, current, r):
        positive = pb.dwell[pb.dwell > 0]
        scale = float(np.median(positive)) if positive.size else 1.0
        return [{"zeta": z, "tau_d": scale * f} for z in (0.1, 0.5) for f in (0.1, 1.0, 10.0)]

    def signature(self, pb, r, params):
        c = correlation(r, np.log1p(pb.dwell))
        return f"the break-away force rises with the dwell time (r = {c:.2f} against ln(1 + dwell))"
