"""``viscous-power``: σ·sgn(v)·|v|ⁿ in place of σ·v: friction that rises
with speed along a curve (a lubricated gear, a seal; n = 2 is quadratic drag)."""

from __future__ import annotations

import numpy as np

from ..residuals import correlation
from .base import Effect, Param, sliding_unseen, _project

#: The range of the exponent n.
EXPONENT_BOUNDS = (0.2, 3.0)
#: A Coulomb level below this share of the force scale has been taken by the curve.
LEVEL_TAKEN = 1e-6
#: Exponents the fit starts from.
START_EXPONENTS = (0.4, 1.0, 2.0)


def _sigma_bounds(sc):
    # σ·speedⁿ is a force: the bound holds 100 times the force scale at any n of the range
    lo, hi = EXPONENT_BOUNDS
    return 0.0, 100 * sc.force * max(sc.speed ** -lo, sc.speed ** -hi)


def power_term(v, sigma, n):
    """σ·sgn(v)·|v|ⁿ [N] at velocities ``v`` [m/s]."""
    v = np.asanyarray(v, dtype=float)
    return sigma * np.sign(v) * np.abs(v) ** n


class ViscousPower(Effect):
    name = "viscous-power"
    kinds = ("timeseries", "steady")
    off = {"sigma": 0.0}
    params = (Param("sigma", "N·(s/m)^n", _sigma_bounds),
              Param("n", "", lambda sc: EXPONENT_BOUNDS, exponent_of="sigma"))
    description = "friction rising with speed along a curve, σ·sgn(v)·|v|ⁿ"
    regressor = {"timeseries": "v", "steady": "v"}
    extends = ("viscous", {"n": 1.0})

    def unresolved(self, pb, params):
        """A record that never slides does not show a rise with speed; and in a time
        series a concave σ·|v|ⁿ that takes the whole Coulomb level (Fc driven to its
        bound 0, as a nearly flat |v|^0.3 can) is the level, not a rise: it switches
        with the direction as a level does and takes, after each reversal, whatever
        transient the record holds. On a steady curve the rows are separate set-points:
        the curve's shape over the speeds shown is what they hold, and what it implies
        below the slowest is said by the ``beyond-data`` warning on Fc."""
        unseen = sliding_unseen(pb, params)
        if unseen:
            return unseen
        levels = [params[k] for k in ("Fc", "Fc_neg") if k in params]
        if pb.kind == "timeseries" and params["n"] < 1.0 \
                and min(levels) <= LEVEL_TAKEN * pb.scales.force:
            return (f"its σ·|v|^{params['n']:.2g} takes the Coulomb level (Fc = "
                    f"{min(levels):.3g} {pb.data.unit('N')}): a curve that flat stands in "
                    f"for the level, not for a rise with speed")
        return None

    def target(self, pb, p, v):
        return power_term(v, p["sigma"], p["n"])

    def starts(self, pb, current, r):
        return [{"sigma": max(_project(r, power_term(pb.v, 1.0, n)), 0.0), "n": n}
                for n in START_EXPONENTS]

    def signature(self, pb, r, params):
        sliding, v, d = pb.sliding_rows(), pb.regressor_speed(), pb.signed_direction()
        n = params.get("n", 1.0)
        speed = np.abs(v[sliding])
        c_curve = correlation(r[sliding] * d[sliding], speed ** n)
        return (f"the residual grows with |v| in the direction of motion along a curve, "
                f"closest to |v|^{n:.2g} (r = {c_curve:.2f})")


__all__ = ["EXPONENT_BOUNDS", "ViscousPower", "power_term"]
