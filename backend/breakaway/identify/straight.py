"""A curve's straight form: the model with a curve that holds a line as a special case
(σ·|v|ⁿ holds σ·|v| at n = 1) fitted with the line in its place, which the nested-curve
rule (:mod:`.curves`) and the retried Stribeck drop (:mod:`.drop`) both weigh."""

from __future__ import annotations

from .effects import EFFECTS
from .fitting import FitResult, family, fit_model


def straight_forms(data, fit: FitResult):
    """Each curve of ``fit`` with its model fitted on ``data`` in the curve's straight
    form (the same held and tied parameters, from ``fit``'s values): pairs of the curve
    and that fit."""
    for effect in fit.effects:
        nested = EFFECTS[effect].extends
        if nested is None or nested[0] in fit.effects:
            continue
        straight = tuple(nested[0] if e == effect else e for e in fit.effects)
        start = {k: v for k, v in fit.params.items() if k not in nested[1]}
        try:
            yield effect, fit_model(data, straight, starts=[start], screen=1, **family(fit))
        except (ValueError, FloatingPointError):
            continue


__all__ = ["straight_forms"]
