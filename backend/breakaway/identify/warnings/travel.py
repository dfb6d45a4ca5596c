"""``short-travel``: the residual depends on x at a scale the travel cannot hold twice,
so ``ripple`` was not tried there."""

from __future__ import annotations

from ..effects import MIN_RIPPLE_PERIODS, long_wavelength
from ..fitting import FitResult
from . import warning


def travel_warnings(fit: FitResult, structure: list[dict]) -> list[dict]:
    """``short-travel`` when x explains a tenth of the residual at a long wavelength."""
    if fit.problem.kind != "timeseries" or not structure or "ripple" in fit.effects:
        return []
    strength = {s["against"]: s["strength"] for s in structure}.get("x", 0.0)
    lam = long_wavelength(fit.problem, fit.residual())
    if strength < 0.1 or lam is None:
        return []
    travel = fit.problem.scales.travel
    return [warning("short-travel", None, (
        f"the residual depends on x ({100 * strength:.0f} % of its variance), most strongly "
        f"at a wavelength of about {lam:.3g} over a travel of {travel:.3g}: the travel holds "
        f"fewer than {MIN_RIPPLE_PERIODS:g} such periods, so ripple is not tried there"))]


__all__ = ["travel_warnings"]
