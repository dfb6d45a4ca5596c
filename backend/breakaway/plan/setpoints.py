"""Constant-speed set-points as a family of runs: the steady friction F(v) of (E2),
measured at +v and at −v in each run.

``F(±v) = ±m(v)`` with ``m(v) = g(v) + σ·vⁿ``: the two directions say the same about
the parameters of a symmetric curve, so a run counts as two measurements of m(v). The
steady curve does not depend on the presliding scale ``s``; a rig holds no speed below
the slowest it can keep steady, so a Stribeck drop below that speed is out of reach.
"""

from __future__ import annotations

import numpy as np

from .curve import magnitude
from .family import Candidates, Information, from_rows
from .programme import empty_csv, run_order, setpoints_csv

#: Measurements per run (+v and −v).
DIRECTIONS = 2


class SetPoints:
    """Constant-speed set-points, both directions."""

    name = "steady"
    depends = ("Fc", "Fs", "V", "delta", "sigma", "n")
    header = ("run", "v")
    #: the limits its runs are bound by
    limits = ("u_max", "v_max", "v_min")

    def candidates(self, P, setting, middle: int = 0) -> Candidates:
        """Speeds from the slowest the rig holds to ``v_max`` where the force the rig
        must apply stays below ``u_max`` at the middle draw (the best guess)."""
        lim = setting.limits
        if lim.v_min >= lim.v_max:
            return Candidates({}, f"v_min = {lim.v_min:.3g} is not below v_max = "
                                  f"{lim.v_max:.3g} {setting.units['v']}")
        v = np.geomspace(lim.v_min, lim.v_max, setting.grid)
        force = magnitude(v, P)[0][middle]
        within = force <= lim.u_max
        if not within.any():
            return Candidates({}, (
                f"at every speed between v_min and v_max the friction exceeds u_max = "
                f"{lim.u_max:.4g} {setting.units['F']} (it is at least "
                f"{float(np.min(force)):.4g} {setting.units['F']})"))
        return Candidates({"v": v[within]})

    def information(self, cands: Candidates, P, setting, names, middle: int = 0) -> Information:
        value, _, partial = magnitude(cands.points["v"], P)
        # at a draw where holding the speed takes more than u_max, the run yields nothing
        usable = value <= setting.limits.u_max
        return from_rows(partial, names, np.sqrt(DIRECTIONS) / setting.noise, usable,
                         {"F": value})

    def design(self, counts, cands: Candidates, info: Information, mid: int, setting) -> dict:
        index = np.repeat(np.arange(counts.size), counts)
        return {"speeds": cands.points["v"][index].tolist(),
                "predicted_F": info.predicted["F"][mid, index].tolist()}

    def programme(self, design: dict | None, setting, reason: str = "") -> str:
        if not design or not design["speeds"]:
            return empty_csv(self.header, reason)
        speeds = np.asarray(design["speeds"])
        return setpoints_csv(speeds[run_order(speeds.size)], setting.units)


__all__ = ["DIRECTIONS", "SetPoints"]
