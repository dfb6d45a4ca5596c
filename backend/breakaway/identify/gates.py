"""The gate an effect passes before it is accepted (MODEL.md §7–§8): the BIC falls
clearly, the RMSE falls, and the effect either removes its share of the residual above
the noise floor or, where something outside the library is larger, shows its own
signature clearly: it lowers the error consistently along the whole record.

An effect that is there acts wherever its cause does (a direction difference in every
stroke, an inertia at every acceleration), so it lowers the squared error in nearly
every stretch of the record, however large the misfit beside it. A stand-in that
absorbs part of an out-of-library misfit helps where the two happen to line up and
hurts elsewhere.

Either way the signature must be its own: an effect whose regressor moves in step with
another variable of the record (inertia's a on a single-frequency sine is −ω²·x, which a
stiffness in series would give as well) cannot be told from a dependence on that
variable that the library lacks."""

from __future__ import annotations

import math

import numpy as np
from scipy.ndimage import uniform_filter1d

from .effects import EFFECTS
from .fitting import FitResult, smooth_order
from .residuals import correlation

#: A BIC drop of 10 is "very strong" evidence (Kass & Raftery 1995).
MIN_BIC_DROP = 10.0
#: An accepted effect removes at least this share of the residual variance above the
#: noise floor (an effect that is there removes nearly all of its own part).
MIN_EXCESS_EXPLAINED = 0.25
#: ... and at least this relative share of the RMSE.
MIN_RMSE_GAIN = 0.01


#: Contiguous stretches of the record (along the kind's regressor) the gain is judged in.
CONSISTENCY_BLOCKS = 10
#: A consistent gain lowers the squared error in at least this share of them ...
CONSISTENT_SHARE = 0.8
#: ... and its mean over them is at least this many standard errors.
CONSISTENT_T = 4.0
#: An effect's regressor is not its own when it correlates beyond this with another
#: variable of the record ...
OWN_REGRESSOR = 0.9
#: ... averaged over this share of the rows (1/200) along the record.
SMOOTHING_SHARE = 200


def collinear_with(problem, effect) -> str | None:
    """The variable of the record that ``effect``'s regressor moves in step with, if
    any (None: the regressor is its own). The regressor is averaged over a few rows
    along the record first, so that the noise of an estimated acceleration does not
    hide how it moves."""
    name = EFFECTS[effect].regressor[problem.kind]
    variables = problem.variables()
    values = variables.get(name, getattr(problem, name, None))
    if values is None:
        return None
    order = smooth_order(problem, np.arange(problem.data.n))
    smoothed = np.empty(values.size)
    smoothed[order] = uniform_filter1d(np.asarray(values, dtype=float)[order],
                                       max(5, values.size // SMOOTHING_SHARE), mode="nearest")
    for other, series in variables.items():
        if other != name and abs(correlation(smoothed, series)) > OWN_REGRESSOR:
            return other
    return None


def consistency(current: FitResult, trial: FitResult) -> tuple[float, float]:
    """The share of :data:`CONSISTENCY_BLOCKS` stretches of the record in which
    ``trial`` lowers the squared error of ``current``, and the t statistic of the
    stretches' gains."""
    rows = np.arange(current.problem.data.n)
    order = smooth_order(current.problem, rows)
    gain = (current.residual() ** 2 - trial.residual() ** 2)[order]
    parts = np.array([part.sum() for part in np.array_split(gain, CONSISTENCY_BLOCKS)])
    spread = float(np.std(parts, ddof=1))
    t = float(np.mean(parts)) / (spread / math.sqrt(parts.size)) if spread > 0 else math.inf
    return float(np.mean(parts > 0)), t


def gate(current: FitResult, trial: FitResult, noise: float, added: int = 1) -> str | None:
    """Why ``trial`` does not improve on ``current`` enough (None: it passes)."""
    new = [e for e in trial.effects if e not in current.effects]
    twin = collinear_with(trial.problem, new[0]) if len(new) == 1 else None
    if twin is not None:
        return (f"its regressor moves in step with {twin}, so on these data it cannot be "
                f"told from a dependence on {twin}, which the library lacks")
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
    if share >= MIN_EXCESS_EXPLAINED * added:
        return None
    short = (f"it explains {100 * share:.0f} % of the residual variance above the noise "
             f"floor, less than the {100 * MIN_EXCESS_EXPLAINED * added:.0f} % required")
    if added > 1 or len(new) != 1:
        return short
    positive, t = consistency(current, trial)
    if positive >= CONSISTENT_SHARE and t >= CONSISTENT_T:
        return None  # its own signature is clear next to a larger misfit
    return (f"{short}, and its gain is not consistent along the record (it lowers the "
            f"error in {100 * positive:.0f} % of {CONSISTENCY_BLOCKS} stretches, t = {t:.1f})")


__all__ = ["CONSISTENCY_BLOCKS", "MIN_BIC_DROP", "MIN_EXCESS_EXPLAINED", "MIN_RMSE_GAIN",
           "consistency", "gate"]
