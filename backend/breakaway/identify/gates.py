"""The gate an effect passes before it is accepted (MODEL.md §7–§8): the BIC falls
clearly, the RMSE falls, and the effect removes its share of the residual above the
noise floor."""

from __future__ import annotations

from .fitting import FitResult

#: A BIC drop of 10 is "very strong" evidence (Kass & Raftery 1995).
MIN_BIC_DROP = 10.0
#: An accepted effect removes at least this share of the residual variance above the
#: noise floor (an effect that is there removes nearly all of its own part).
MIN_EXCESS_EXPLAINED = 0.25
#: ... and at least this relative share of the RMSE.
MIN_RMSE_GAIN = 0.01


def gate(current: FitResult, trial: FitResult, noise: float, added: int = 1) -> str | None:
    """Why ``trial`` does not improve on ``current`` enough (None: it passes)."""
    drop = current.bic - trial.bic
    if not drop >= MIN_BIC_DROP * added:
        return f"the BIC falls by {drop:.1f}, less than the {MIN_BIC_DROP * added:g} required"
    if trial.rmse > (1 - MIN_RMSE_GAIN) * current.rmse:
        gain = 100 * (1 - trial.rmse / current.rmse)
        return f"the RMSE falls by only {gain:.2g} %"
    excess = current.rmse**2 - noise**2
    if excess <= 0:
        return "the residual is already at the noise floor"
    share = (current.rmse**2 - trial.rmse**2) / excess
    if share < MIN_EXCESS_EXPLAINED * added:
        return (f"it explains {100 * share:.0f} % of the residual variance above the noise "
                f"floor, less than the {100 * MIN_EXCESS_EXPLAINED * added:.0f} % required")
    return None


__all__ = ["MIN_BIC_DROP", "MIN_EXCESS_EXPLAINED", "MIN_RMSE_GAIN", "gate"]
