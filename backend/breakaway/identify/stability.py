"""An effect that is there holds in both halves of a time series.

On a real machine the residual is largely what the library lacks, and an effect can win
the held-out test by absorbing part of that misfit where the misfit repeats (a curve
σ·|v|ⁿ taking a transient after each reversal). Such a stand-in has no value of its
own: fitted on the first and on the second half of the record it takes whatever each
half's misfit needs. A friction effect does not change its parameters halfway through a
record (a drift is a parameter of its own), so the accepted model is refitted on each
half and the effect's parameters must agree.

Only what a half determines votes: a parameter that a half's fit does not determine
(on a bound, along a flat direction, a relative standard error above 1) says nothing
about the effect. Inside one half of a
constant-acceleration run m_e·a is a constant like Fc, and the half gives m_e whatever
value its Fc leaves. Where both halves determine a parameter, their values agree within
:data:`RELATIVE_AGREEMENT` of the larger or within :data:`AGREEMENT_SIGMAS` combined
standard errors (an angle within :data:`PHASE_AGREEMENT`, read at the middle of the travel).

Steady and break-away files are sets of separate measurements, not a record in time;
the check is for time series.
"""

from __future__ import annotations

import math

import numpy as np

from .csvdata import Dataset
from .effects import EFFECTS
from .fitting import FitResult, family, fit_model

#: Parameter values of the two halves agree within this share of the larger ...
RELATIVE_AGREEMENT = 0.25
#: ... or within this many combined standard errors ...
AGREEMENT_SIGMAS = 2.0
#: ... and an angle within this [rad].
PHASE_AGREEMENT = 0.5
#: A half's value of an effect's size votes only where its multiple correlation with the
#: other parameters of the half's fit (:func:`multiple_correlation`) stays at or below this.
VOTE_CORRELATION = 0.9
#: An eigenvalue of a correlation matrix this small (of its largest) is a flat direction.
FLAT_EIGENVALUE = 1e-10
#: Evaluations of each half's refit (from the whole record's solution).
HALF_EVALUATIONS = 60


def _halves(n: int) -> list[np.ndarray]:
    index = np.arange(n)
    return [np.flatnonzero(index < n // 2), np.flatnonzero(index >= n // 2)]


def _half_fits(data: Dataset, fit: FitResult, halves: list[np.ndarray]):
    return [fit_model(data, fit.effects, starts=[fit.params], rows=rows, screen=1,
                      max_nfev=HALF_EVALUATIONS, **family(fit)) for rows in halves]


def _agree(name, spec, a: FitResult, b: FitResult, centre: float = 0.0) -> bool:
    p1, p2 = a.params[name], b.params[name]
    if not spec.relative:
        if "wavelength" in a.params:
            # a phase is read where the record travels, not at x = 0: far from the origin
            # a wavelength that differs in its third digit turns the phase at x = 0 by
            # whole radians while the two ripples lie on each other over the data
            p1 += 2 * math.pi * centre / a.params["wavelength"]
            p2 += 2 * math.pi * centre / b.params["wavelength"]
        return abs(math.remainder(p1 - p2, 2 * math.pi)) <= PHASE_AGREEMENT
    gap = abs(p1 - p2)
    return gap <= max(RELATIVE_AGREEMENT * max(abs(p1), abs(p2)),
                      AGREEMENT_SIGMAS * math.hypot(a.stderr[name] or 0.0, b.stderr[name] or 0.0))


def _holds(half: FitResult, name: str, size: bool = False) -> bool:
    """Whether ``half`` determines ``name``'s value: off its bounds, with a standard error
    no larger than the value. A shape parameter correlated with another of the same model
    still votes (both halves fit the same model); an effect's size does not when a
    multiple correlation above :data:`VOTE_CORRELATION` ties it to the other parameters:
    inside a half of a constant-acceleration run m_e·a moves with the levels (the ramps in
    and out of the constant keep each pair's correlation under 0.99), and the half gives
    m_e whatever they leave."""
    a = half.assessment
    why, se = a.why.get(name), half.stderr.get(name)
    if why is not None and not why.startswith("correlated:") or se is None:
        return False
    if half.problem.spec(name).relative and se > abs(half.params[name]):
        return False
    if not size or a.correlation is None or name not in a.names:
        return True
    return multiple_correlation(a.correlation, a.names.index(name)) <= VOTE_CORRELATION


def multiple_correlation(correlation, index: int) -> float:
    """The multiple correlation of parameter ``index`` with all the others of a fit
    (``correlation`` its matrix): √(1 − 1/(R⁻¹)ᵢᵢ), 1 along a flat direction. No pair
    need show it: in the first half of a constant-acceleration run m_e·a is what Fc, Fs,
    V and δ together make (multiple correlation 0.996), while no one of them correlates
    with m_e above 0.52."""
    R = np.nan_to_num(np.asarray(correlation, dtype=float))
    if R.shape[0] < 2:
        return 0.0
    values, vectors = np.linalg.eigh(R)
    flat = values <= FLAT_EIGENVALUE * max(float(values[-1]), 1.0)
    if np.any(np.abs(vectors[index, flat]) > FLAT_EIGENVALUE):
        return 1.0  # the parameter moves along a direction the fit leaves flat
    precision = float(np.sum(vectors[index, ~flat] ** 2 / values[~flat]))
    return math.sqrt(max(0.0, 1.0 - 1.0 / precision)) if precision > 0 else 0.0


def unstable(data: Dataset, fit: FitResult, effect: str) -> str | None:
    """Why ``effect``'s parameters in ``fit`` do not hold in both halves of the record
    (None: they do where both halves determine them, or ``data`` is not a time series)."""
    if data.kind != "timeseries" or EFFECTS[effect].acts_through == "t":
        # an effect through time (a drift) shows its own form instead (its
        # ``unresolved``: one monotone trend in every stroke and both directions):
        # halves in time cut its regressor's range in two, where an unknown dependence
        # that moves with time (a position profile the strokes sweep) pulls each half
        # its own way
        return None
    try:
        first, second = _half_fits(data, fit, _halves(data.n))
    except (ValueError, FloatingPointError):
        return None  # a half too short to fit says nothing either way
    centre = float(np.mean(data.columns["x"]))
    for name in EFFECTS[effect].keys:
        size = name in EFFECTS[effect].size_keys
        if not (_holds(first, name, size) and _holds(second, name, size)):
            continue  # only what both halves determine votes
        if not _agree(name, fit.problem.spec(name), first, second, centre):
            return (f"a stand-in for something outside the library: {name} takes "
                    f"{first.params[name]:.4g} in the first half of the record and "
                    f"{second.params[name]:.4g} in the second")
    return None


__all__ = ["RELATIVE_AGREEMENT", "unstable"]
