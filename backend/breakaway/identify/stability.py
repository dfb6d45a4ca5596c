"""An effect that is there holds in both halves of a time series.

On a real machine the residual is largely what the library lacks, and an effect can win
the gates by absorbing part of that misfit (a curve σ·|v|ⁿ taking a transient after each
reversal, an offset taking its mean). Such a stand-in has no value of its own: fitted
on the first and on the second half of the record it takes whatever each half's misfit
needs. A friction effect does not change its parameters halfway through a record (a
drift is a parameter of its own), so the accepted model is refitted on each half and
the effect's parameters must agree:

each parameter's two values agree within :data:`RELATIVE_AGREEMENT` of the larger, or,
where both halves give it a sharp standard error, within :data:`AGREEMENT_SIGMAS`
combined standard errors (an angle within :data:`PHASE_AGREEMENT`). A parameter the
data tie to another (a correlation above 0.99) still has a value in each half, and a
true one keeps it. Where a half holds a value only loosely (its standard error above
:data:`SHARP` of it), a difference counts only if a half refuses the whole record's
parameters, its own fit better by the BIC's bar (:data:`~.gates.MIN_BIC_DROP`, its own
parameters counted): a half of slow strokes that trades σ against the Stribeck curve
fits as well with the record's σ, and says nothing against it.

Steady and break-away files are sets of separate measurements, not a record in time;
the check is for time series.
"""

from __future__ import annotations

import math

import numpy as np

from .csvdata import Dataset
from .effects import EFFECTS
from .fitting import FitResult, _cost, fit_model
from .gates import MIN_BIC_DROP

#: Parameter values of the two halves agree within this share of the larger ...
RELATIVE_AGREEMENT = 0.25
#: ... or within this many combined standard errors where both are below
#: :data:`SHARP` of their values ...
AGREEMENT_SIGMAS = 2.0
SHARP = 0.25
#: ... and an angle within this [rad].
PHASE_AGREEMENT = 0.5
#: Evaluations of each half's refit (from the whole record's solution).
HALF_EVALUATIONS = 60


def _halves(n: int) -> list[np.ndarray]:
    index = np.arange(n)
    return [np.flatnonzero(index < n // 2), np.flatnonzero(index >= n // 2)]


def _half_fits(data: Dataset, fit: FitResult, halves: list[np.ndarray]):
    return [fit_model(data, fit.effects, starts=[fit.params], rows=rows, screen=1,
                      max_nfev=HALF_EVALUATIONS) for rows in halves]


def _refuses(half: FitResult, params: dict, rows: np.ndarray) -> bool:
    """Whether ``half``'s own fit beats ``params`` on its ``rows`` by the BIC's bar, its
    own parameters counted (n·ln of the cost ratio − k·ln n)."""
    own, theirs = _cost(half.problem, half.params, rows), _cost(half.problem, params, rows)
    n, k = rows.size, len(half.problem.names)
    return n * math.log(max(theirs, 1e-300) / max(own, 1e-300)) - k * math.log(n) > MIN_BIC_DROP


def _agree(name, spec, a: FitResult, b: FitResult) -> bool:
    p1, p2 = a.params[name], b.params[name]
    if not spec.relative:
        return abs(math.remainder(p1 - p2, 2 * math.pi)) <= PHASE_AGREEMENT
    gap = abs(p1 - p2)
    if gap <= RELATIVE_AGREEMENT * max(abs(p1), abs(p2)):
        return True
    if not (_sharp(a, name) and _sharp(b, name)):
        return False
    return gap <= AGREEMENT_SIGMAS * math.hypot(a.stderr[name], b.stderr[name])


def _sharp(half: FitResult, name: str) -> bool:
    """Whether ``half`` holds ``name`` to :data:`SHARP` of its value."""
    se = half.stderr.get(name)
    return se is not None and se <= SHARP * abs(half.params[name])


def unstable(data: Dataset, fit: FitResult, effect: str) -> str | None:
    """Why ``effect``'s parameters in ``fit`` do not hold in both halves of the record
    (None: they do, or ``data`` is not a time series)."""
    if data.kind != "timeseries":
        return None
    try:
        halves = _halves(data.n)
        first, second = _half_fits(data, fit, halves)
    except (ValueError, FloatingPointError):
        return None  # a half too short to fit says nothing either way
    problem = fit.problem
    refused = None  # computed once, where a loosely held value differs
    for name in EFFECTS[effect].keys:
        spec = problem.spec(name)
        if not _agree(name, spec, first, second):
            if spec.relative and not (_sharp(first, name) and _sharp(second, name)):
                if refused is None:
                    refused = any(_refuses(half, fit.params, rows)
                                  for half, rows in zip((first, second), halves))
                if not refused:
                    continue
            return (f"a stand-in for something outside the library: {name} takes "
                    f"{first.params[name]:.4g} in the first half of the record and "
                    f"{second.params[name]:.4g} in the second")
    return None


__all__ = ["RELATIVE_AGREEMENT", "unstable"]
