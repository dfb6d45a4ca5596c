"""Least-squares fits of the base model and of the base model with effects.

``fit_model`` returns a :class:`FitResult` whose ``params`` are exactly what
:meth:`Problem.predict` (the model function) takes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares

from .csvdata import Dataset
from .effects import EFFECTS
from .identifiability import Assessment, assess
from .models import Problem, problem_for
from .noise import orderings
from .starts import base_starts, effect_starts


class FitError(ValueError):
    """The data cannot be fitted (too few rows for the parameters, no usable start)."""


@dataclass
class FitResult:
    """One fitted model.

    Attributes
    ----------
    effects : tuple of str
    params : dict
        Fitted values keyed as in the report (``Fc``, ``Fs``, ``V``, ``delta``, ``s``,
        effects' keys), the input of :meth:`Problem.predict`.
    stderr : dict
        Standard errors from the Jacobian (delta method through the transforms);
        None where the data give none (:mod:`breakaway.identify.identifiability`).
    determined : dict
        Whether the data determine each parameter; ``why`` says why not.
    rmse : float
        Root mean square of measured − predicted F over the fitted rows [N].
    bic : float
        ``n·ln(RSS/n) + p·ln(n)``, RSS weighted by the rows' weights (:func:`row_scales`).
    n : int
        Rows fitted.
    prediction : numpy.ndarray
        Predicted F for every row of the dataset (fitted or not).
    theta : numpy.ndarray
        The solution in the fit's coordinates (:meth:`Problem.to_theta`).
    jac : numpy.ndarray or None
        Jacobian of the fitted rows' weighted residuals (:func:`row_scales`) with
        respect to ``theta`` at the solution, shape (n, p); what a held-out refit starts
        from (:mod:`.heldout`).
        None for records longer than :data:`KEEP_JACOBIAN_ROWS`, which are never
        searched on every row (they are screened on blocks).
    rows : numpy.ndarray
        The rows fitted (indices).
    """

    effects: tuple[str, ...]
    params: dict
    rmse: float
    bic: float
    n: int
    prediction: np.ndarray
    problem: Problem
    assessment: Assessment
    theta: np.ndarray = None
    jac: np.ndarray | None = None
    rows: np.ndarray | None = None

    @property
    def stderr(self) -> dict:
        return self.assessment.stderr

    @property
    def determined(self) -> dict:
        return self.assessment.determined

    def residual(self) -> np.ndarray:
        """Measured minus predicted F for every row [N]."""
        return self.problem.measured - self.prediction

    @property
    def weighted_rss(self) -> float:
        """The fitted rows' residual sum of squares as the fit weighs them [N²]."""
        return _weighted_rss(self.problem, self.residual(), self.rows)


def _weighted_rss(problem, residual, rows) -> float:
    weighted = residual[rows] * row_scales(problem.data, rows)
    return float(np.dot(weighted, weighted))


def bic(rss: float, n: int, n_params: int) -> float:
    """Bayesian information criterion of a Gaussian least-squares fit."""
    return n * math.log(max(rss, 1e-300) / n) + n_params * math.log(n)


# ---------------------------------------------------------------------------------
# the fit
# ---------------------------------------------------------------------------------


def row_scales(data: Dataset, rows) -> np.ndarray | float:
    """What each of ``rows``' residuals is multiplied by in a fit: the square root of
    its weight (:attr:`~.csvdata.Dataset.weights`), or 1 where every row counts alike.

    A row whose predicted force x's resolution makes uncertain (just after a reversal,
    where (E6') is steep, or where an encoder's count is a large share of the presliding
    distance) has a larger error variance than the force's noise; weighted by the
    inverse of that variance, the fit is the maximum-likelihood one, and such rows no
    longer pull the Stribeck levels and the viscous term towards a reading of x."""
    return 1.0 if data.weights is None else np.sqrt(data.weights[rows])


def weighted_rms(residual, weights=None) -> float:
    """The root mean square of ``residual`` [N] with its rows weighted by ``weights``
    (plain for None)."""
    r2 = np.square(residual)
    if weights is None:
        return math.sqrt(float(np.mean(r2)))
    return math.sqrt(float(np.sum(weights * r2)) / float(np.sum(weights)))


def weighted_rmse(fit: "FitResult") -> float:
    """``fit``'s root mean square residual with its rows weighted as in the fit
    (:func:`row_scales`; the plain RMSE where every row counts alike) [N]."""
    weights = fit.problem.data.weights
    if weights is None:
        return fit.rmse
    return weighted_rms(fit.residual(), weights)


def _cost(problem, params, rows):
    value = _weighted_rss(problem, problem.predict(params) - problem.measured, rows)
    return value if math.isfinite(value) else math.inf


def _solve(problem, theta0, rows, max_nfev):
    lo, hi = problem.bounds()
    theta0 = np.clip(theta0, lo, hi)
    # keep the start strictly inside the bounds: trf needs an interior point
    span = hi - lo
    theta0 = np.clip(theta0, lo + 1e-9 * span, hi - 1e-9 * span)

    scales = row_scales(problem.data, rows)
    target = problem.measured[rows]
    # every row (the usual case): no copy of the prediction per evaluation
    every_row = rows.size == problem.data.n and np.array_equal(rows, np.arange(rows.size))

    def residual(theta):
        prediction = problem.predict(problem.to_params(theta))
        r = ((prediction if every_row else prediction[rows]) - target) * scales
        broken = ~np.isfinite(r)
        if broken.any():
            r[broken] = 1e6 * problem.scales.force
        return r

    return least_squares(residual, theta0, bounds=(lo, hi), method="trf", x_scale="jac",
                         max_nfev=max_nfev)


def fit_model(data: Dataset, effects=(), starts=None, rows=None, max_nfev=None,
              screen=3, fixed=None, ties=None) -> FitResult:
    """Fit the model with ``effects`` to ``data`` by bounded least squares.

    Parameters
    ----------
    data : Dataset
        Parsed measurement.
    effects : sequence of str, optional
        Effects of the library added to the base model.
    starts : list of dict, optional
        Starting parameter sets (full dictionaries). By default a grid derived from the
        data (:func:`base_starts`), which needs ``effects`` to be empty.
    rows : array of bool or int, optional
        Rows that enter the fit (all by default); the prediction still covers every row,
        so a timeseries keeps its history.
    max_nfev : int, optional
        Evaluation budget of the final polish.
    screen : int, optional
        The best ``screen`` starts (by their initial cost) are polished.
    fixed : dict, optional
        Parameters held at given values (their ``stderr`` is reported as 0).
    ties : dict, optional
        Coulomb levels held equal to their Stribeck level (``{"Fc": "Fs"}``): the model
        without a Stribeck drop (:class:`~.models.Problem`).

    Returns
    -------
    FitResult
    """
    problem = problem_for(data, tuple(effects), dict(fixed or {}), ties)
    rows = np.arange(data.n) if rows is None else np.asarray(rows)
    if rows.dtype == bool:
        rows = np.flatnonzero(rows)
    n = rows.size
    if n <= len(problem.names) + 1:
        raise FitError(f"{n} rows cannot determine {len(problem.names)} parameters")
    if starts is None:
        if effects:
            raise ValueError("starts are needed when effects are given")
        starts = base_starts(problem)
    costs = [_cost(problem, s, rows) for s in starts]
    order = np.argsort(costs)[:screen]
    if not math.isfinite(costs[order[0]]):
        raise FitError("no starting point gives a finite prediction")
    # a short polish of each screened start, then a full one of the best
    n_params = len(problem.names)
    budget = max_nfev or 60 * (n_params + 1)
    best = None
    if len(order) > 1:
        for i in order:
            result = _solve(problem, problem.to_theta(starts[i]), rows, 8 * (n_params + 1))
            if best is None or result.cost < best.cost:
                best = result
        theta = best.x
    else:
        theta = problem.to_theta(starts[order[0]])
    final = _solve(problem, theta, rows, budget)
    best = final if best is None or final.cost <= best.cost else best
    params = problem.to_params(best.x)
    prediction = problem.predict(params)
    residual = problem.measured - prediction
    r, rss = residual[rows], _weighted_rss(problem, residual, rows)
    order = smooth_order(problem, rows)
    assessment = assess(problem, best.x, best.jac, best.cost, n, best.active_mask,
                        best.fun, order)
    assessment = _levels_without_drop(problem, params, rows, assessment, order)
    if not problem.level_only:
        # a model without a drop: each Coulomb level is its Stribeck level's result
        for low, level in problem.tied.items():
            if level in problem.names:
                for field in (assessment.stderr, assessment.determined, assessment.why):
                    field[low] = field[level]
    # the RMSE is the plain one the report shows; the BIC is the weighted fit's
    return FitResult(problem.effects, params, math.sqrt(float(np.dot(r, r)) / n),
                     bic(rss, n, len(problem.names)), n, prediction, problem, assessment,
                     best.x, best.jac if n <= KEEP_JACOBIAN_ROWS else None, rows)


#: Fits of more rows than this do not keep their Jacobian (:attr:`FitResult.jac`).
KEEP_JACOBIAN_ROWS = 200_000


#: Each Stribeck level with its Coulomb level (Fc when Fs = Fc).
LEVEL_PAIRS = (("Fc", "Fs"), ("Fc_neg", "Fs_neg"))


def smooth_order(problem: Problem, rows) -> np.ndarray:
    """Positions within ``rows`` in the order along which a residual is smooth (time; v;
    k within one direction and dwell: :func:`.noise.orderings`)."""
    rank = np.empty(problem.data.n, dtype=np.int64)
    rank[np.concatenate(orderings(problem)[0])] = np.arange(problem.data.n)
    return np.argsort(rank[rows], kind="stable")


def _levels_without_drop(problem: Problem, params: dict, rows, assessment: Assessment,
                         order=None):
    """When Fs ends on its bound Fs = Fc (no Stribeck drop in the data), Fc
    is still a result: its standard error (and whether it is determined) comes from
    the model without the drop, Fc = Fs with V and δ held, where V and δ describe
    nothing. The same for the negative direction's levels."""
    ties = {low: level for low, level in LEVEL_PAIRS
            if low in problem.names and assessment.bound.get(level) == "lower"}
    if not ties:
        return assessment
    held = {name: params[name] for name in ("V", "delta") if name in problem.names}
    reduced = problem_for(problem.data, problem.effects, {**problem.fixed, **held}, ties=ties)
    result = _solve(reduced, reduced.to_theta(params), rows, 1)
    without = assess(reduced, result.x, result.jac, result.cost, rows.size,
                     result.active_mask, result.fun, order)
    for low, level in ties.items():
        assessment.stderr[low] = without.stderr[level]
        assessment.determined[low] = without.determined[level]
        assessment.why[low] = without.why[level]
    return assessment


def family(fit: FitResult) -> dict:
    """The base parameters ``fit``'s model holds or ties (a model without a Stribeck
    drop, a level-only break-away fit), as :func:`fit_model`'s ``fixed`` and ``ties``:
    a model with other effects stays in the same family."""
    problem = fit.problem
    base = problem.base_names
    return {"fixed": {k: v for k, v in problem.fixed.items() if k in base} or None,
            "ties": problem.tied or None}


def refit(data: Dataset, fit: FitResult, rows=None, max_nfev=None) -> FitResult:
    """Fit the same model (its held and tied parameters too) again from ``fit``'s
    parameters (e.g. on other rows)."""
    problem = fit.problem
    return fit_model(data, fit.effects, starts=[fit.params], rows=rows, max_nfev=max_nfev,
                     screen=1, fixed=problem.fixed, ties=problem.tied or None)


def best_base_starts(data: Dataset, count: int = 4) -> list[dict]:
    """The ``count`` base starting points of :func:`base_starts` with the lowest cost."""
    problem = problem_for(data)
    starts = base_starts(problem)
    rows = np.arange(data.n)
    costs = [_cost(problem, s, rows) for s in starts]
    return [starts[i] for i in np.argsort(costs)[:count]]


def fit_with_effect(data: Dataset, current: FitResult, effect: str, rows=None,
                    screen=2, restarts=(), max_nfev=None) -> FitResult:
    """Add ``effect`` to ``current``'s model and fit everything again.

    Starts: ``current``'s parameters with the effect's values read off the residual,
    and the same effect values on each of ``restarts`` (base parameter sets, e.g.
    :func:`best_base_starts`), so a fit is not trapped in the current model's basin.
    """
    kin = family(current)
    problem = problem_for(data, current.effects + (effect,), kin["fixed"], kin["ties"])
    extras = effect_starts(current.problem, effect, current.params, current.residual())
    starts = []
    for origin in (current.params, *restarts):
        starts.extend({**current.params, **origin, **extra} for extra in extras)
    profiled = [p.name for p in EFFECTS[effect].params if p.profiled]
    if profiled:
        return _profiled_fit(data, problem.effects, profiled[0], starts, rows, kin)
    return fit_model(data, problem.effects, starts=starts, rows=rows, screen=screen,
                     max_nfev=max_nfev, **kin)


#: Values of a profiled parameter that get a fit (the best by their starts' cost).
PROFILE_FITS = 3


def _profiled_fit(data, effects, name, starts, rows, kin):
    """Fit with ``name`` held at each start's value (and 0), then free from the best
    (within the model family ``kin``, :func:`family`)."""
    by_value = {}
    for start in starts:
        by_value.setdefault(start[name], []).append(start)
    zero = {**starts[0], name: 0.0}
    by_value.setdefault(0.0, [zero])
    held = kin["fixed"] or {}
    # every value is scored at its starts first; only the most promising are fitted
    index = np.arange(data.n) if rows is None else np.asarray(rows)
    scored = sorted(by_value.items(), key=lambda item: min(
        _cost(problem_for(data, effects, {**held, name: item[0]}, kin["ties"]),
              {**s, name: item[0]}, index)
        for s in item[1]))
    best = None
    n_free = len(problem_for(data, effects, held, kin["ties"]).names) - 1
    for value, group in scored[:PROFILE_FITS]:
        fit = fit_model(data, effects, starts=group, rows=rows, screen=1,
                        fixed={**held, name: value}, ties=kin["ties"],
                        max_nfev=8 * (n_free + 1))
        if best is None or fit.bic < best.bic:
            best = fit
    free = fit_model(data, effects, starts=[best.params], rows=rows, screen=1, **kin)
    return free if free.bic <= best.bic else _evaluated_at(data, effects, best.params, rows, kin)


def _evaluated_at(data, effects, params, rows, kin):
    """The model with every parameter free, evaluated at ``params`` without moving them
    (least_squares stops after its first evaluation), so each parameter gets its
    standard error from the Jacobian there."""
    return fit_model(data, effects, starts=[params], rows=rows, screen=1, max_nfev=1, **kin)


__all__ = ["FitError", "FitResult", "best_base_starts", "bic", "family", "fit_model",
           "fit_with_effect", "refit", "row_scales", "weighted_rms", "weighted_rmse"]
