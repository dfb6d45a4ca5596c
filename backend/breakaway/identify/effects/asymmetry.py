"""``asymmetry``: separate levels in the negative direction."""

from __future__ import annotations

import numpy as np

from .base import Effect, Param, _direction_means, _fmt, _level, _needs_both_directions


class Asymmetry(Effect):
    name = "asymmetry"
    kinds = ("timeseries", "steady", "breakaway")
    params = (Param("Fc_neg", "N", _level),
              Param("Fs_neg", "N", lambda sc: (0.0, 20 * sc.force), gap_of="Fc_neg"))
    description = "separate Coulomb and Stribeck levels in the negative direction"
    regressor = {"timeseries": "v", "steady": "v", "breakaway": "direction"}
    differs_from = {"Fc_neg": "Fc", "Fs_neg": "Fs"}

    def switched_off(self, params):
        return {**params, "Fc_neg": params["Fc"], "Fs_neg": params["Fs"]}

    def unavailable(self, pb):
        return _needs_both_directions(pb)

    def levels(self, pb, p, Fc, Fs, negative):
        return (np.where(negative, p["Fc_neg"], Fc), np.where(negative, p["Fs_neg"], Fs))

    def starts(self, pb, current, r):
        negative = pb.negative_rows
        sel = negative & pb.sliding_rows()
        # measured |F| minus the model's, moving negative (breakaway F_ba is a magnitude)
        sign = 1.0 if pb.kind == "breakaway" else -1.0
        shift = sign * float(np.median(r[sel])) if np.any(sel) else 0.0
        Fc_neg = max(current["Fc"] + shift, 1e-3 * current["Fc"])
        Fs_neg = max(current["Fs"] + shift, Fc_neg)
        return [{"Fc_neg": Fc_neg, "Fs_neg": Fs_neg},
                {"Fc_neg": current["Fc"], "Fs_neg": current["Fs"]}]

    def signature(self, pb, r, params):
        mp, mn = _direction_means(pb, r)
        unit = pb.data.unit("N")
        if pb.kind == "breakaway":
            return (f"the break-away force differs by direction: residual {_fmt(mp)} {unit} "
                    f"for direction +1 and {_fmt(mn)} {unit} for direction -1")
        return (f"the sliding levels differ by direction: measured |F| minus the model's "
                f"is {mp:+.3g} {unit} moving positive and {-mn:+.3g} {unit} moving negative")
