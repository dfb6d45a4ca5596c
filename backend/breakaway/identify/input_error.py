"""What the resolution of x does through the model (the report's ``input_floor``).

The noise floor (:mod:`.noise`) is the noise of the measured force alone. Reading x
with an encoder's step or with noise makes the model's *input* uncertain, most just
after reversals where (E6') is steep: that share of the prediction error is the input
floor, reported beside the noise floor and never added to it. It weights the rows of a
fit and a judgement (:func:`input_weights`), and the residual is set against each row's
own expected error when the report says whether structure is left
(:func:`misfit_ratio`); it is never a reason to refuse an effect.
"""

from __future__ import annotations

import math

import numpy as np

from .noise import NoiseFloor, difference_sigma, orderings


def input_floor(fit, noise: NoiseFloor, errors=None) -> float:
    """The share of ``fit``'s prediction error [N] that the resolution of x sets
    (the report's ``input_floor``): the force error that re-reading the record with x's
    step or noise causes through the model
    (:meth:`~.models.timeseries.TimeseriesProblem.resolution_noise`; ``errors``, its
    rows, where they are at hand); under a commanded force, at least the residual's own
    short-range variation, which is that error seen directly. Never more than what the
    residual leaves above the noise floor."""
    problem = fit.problem
    if problem.kind != "timeseries":
        return 0.0
    if errors is None:
        errors = problem.resolution_errors(fit.params)
    value = float(np.sqrt(np.mean(np.square(errors))))
    if noise.command:
        value = max(value, difference_sigma(fit.residual(), orderings(problem)))
    room = math.sqrt(max(fit.rmse**2 - noise.value**2, 0.0))
    return float(min(value, room))


def misfit_ratio(fit, noise: NoiseFloor, inputs: float, errors=None) -> float:
    """The residual of ``fit`` in units of the error each row is expected to carry:
    ``√(mean(r_i²/(σ² + e_i²)))``, σ the noise floor, e_i the row's error that x's
    resolution sets (``errors``,
    :meth:`~.models.timeseries.TimeseriesProblem.resolution_errors`). About 1 where the
    model explains the data down to their errors.

    Rows are weighed by their own errors, not the record's RMS: x's reading sets a few
    newtons just after each reversal of a seal and nothing elsewhere, and a position
    dependence that the library lacks, several times the noise on every other row, hid
    behind those few rows' share of the RMS (an RMSE of 10.5 N beside an input floor of
    10.1 N). Under a commanded force the input floor is the residual's own short-range
    variation (:func:`input_floor`), known for the record, not row by row: the RMSE is
    set against it."""
    scaled = scaled_residual(fit, noise, errors)
    if scaled is None:
        expected = math.hypot(noise.value, inputs)
        return fit.rmse / expected if expected > 0 else math.inf
    return float(np.sqrt(np.mean(np.square(scaled))))


def scaled_residual(fit, noise: NoiseFloor, errors=None) -> np.ndarray | None:
    """``fit``'s residual, each row in units of its own expected error
    ``√(σ² + e_i²)`` (:func:`misfit_ratio`); None where the rows' errors are not known
    one by one (no ``errors``, a commanded force, a kind other than a time series)."""
    if errors is None or fit.problem.kind != "timeseries" or noise.command:
        return None
    variance = noise.value**2 + np.square(errors)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(variance > 0, fit.residual() / np.sqrt(variance), np.inf)


def input_weights(errors, noise: float, jumps=None, stops=None) -> np.ndarray | None:
    """Each row's weight in a fit and a judgement, ``σ²/(σ² + e_i²)``: e_i the row's
    force error [N] that x's resolution sets
    (:meth:`~.models.timeseries.TimeseriesProblem.resolution_errors`: large just after
    reversals, where (E6') is steep), σ the noise floor ``noise`` [N], or the median
    row's e_i where that is larger. A row where the input makes the prediction
    uncertain counts for less: its error may be the reading of x, not friction; the
    weights single out such rows, so that at least half of the record keeps half its
    weight (a force with no noise of its own, a command, would otherwise hand the whole
    fit to the few rows where x's reading does not matter). ``jumps`` [N], where given,
    adds in quadrature what a's error where it jumps sets through the model
    (:meth:`~.models.timeseries.TimeseriesProblem.acceleration_errors`). ``stops``,
    where given, marks the rows where the body may have halted and turned unseen
    (:meth:`~.models.timeseries.TimeseriesProblem.stop_rows`): the median is taken
    over the other rows, since a servo that sits on a count for half its record under
    a command has no such row to trust, and the rows where it moves are not few. None
    where x is exact (every weight 1)."""
    if errors is not None and jumps is not None:
        errors = np.hypot(errors, jumps)
    if errors is None or not np.any(errors > 0):
        return None
    moving = errors if stops is None or stops.all() else errors[~stops]
    floor = max(noise, float(np.median(moving)), 1e-12 * float(np.max(errors)))
    return floor**2 / (floor**2 + np.square(errors))


__all__ = ["input_floor", "input_weights", "misfit_ratio"]
