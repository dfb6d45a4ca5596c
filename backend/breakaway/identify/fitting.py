"""Least-squares fits of the base model and of the base model with effects.

``fit_model`` returns a :class:`FitResult` whose ``params`` are exactly what
:meth:`Problem.predict` (the model function) takes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares
from scipy.signal import lombscargle

from .csvdata import Dataset
from .models import LOG_PARAMS, Problem


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
        §7 keys), the input of :meth:`Problem.predict`.
    stderr : dict
        Standard errors from the Jacobian (delta method through the transforms);
        ``inf`` where the data do not determine a parameter.
    rmse : float
        Root mean square of measured − predicted F over the fitted rows [N].
    bic : float
        ``n·ln(RSS/n) + p·ln(n)``.
    n : int
        Rows fitted.
    prediction : numpy.ndarray
        Predicted F for every row of the dataset (fitted or not).
    """

    effects: tuple[str, ...]
    params: dict
    stderr: dict
    rmse: float
    bic: float
    n: int
    prediction: np.ndarray
    problem: Problem

    def residual(self) -> np.ndarray:
        """Measured minus predicted F for every row [N]."""
        return self.problem.measured - self.prediction


def bic(rss: float, n: int, n_params: int) -> float:
    """Bayesian information criterion of a Gaussian least-squares fit."""
    return n * math.log(max(rss, 1e-300) / n) + n_params * math.log(n)


# ---------------------------------------------------------------------------------
# initial guesses from the data
# ---------------------------------------------------------------------------------


def _level_guesses(problem: Problem):
    """Coulomb and Stribeck levels from the data (sliding plateaus and peaks)."""
    kind = problem.data.kind
    F = problem.measured
    if kind == "breakaway":
        lo, hi = np.percentile(F, [5, 95])
        return max(float(lo), 1e-6 * problem.scales.force), max(float(hi), float(lo))
    speed = np.abs(problem.v)
    fast = speed >= np.percentile(speed, 70)
    if kind == "timeseries":
        along = np.sign(F) == problem.d
        fast &= along
    Fc = float(np.median(np.abs(F[fast]))) if np.any(fast) else problem.scales.force
    Fs = float(np.percentile(np.abs(F), 98))
    Fc = max(Fc, 1e-6 * problem.scales.force)
    return Fc, max(Fs, Fc)


def base_starts(problem: Problem) -> list[dict]:
    """A grid of starting points for the base parameters (levels from the data)."""
    Fc, Fs = _level_guesses(problem)
    speeds = problem.scales.speed * np.array([0.03, 0.1, 0.3, 1.0])
    starts = []
    for V in speeds:
        for delta in (1.0, 2.0):
            p = {"Fc": Fc, "Fs": max(Fs, 1.02 * Fc), "V": float(V), "delta": delta}
            if problem.data.kind == "timeseries":
                for zs in (0.003, 0.01, 0.03, 0.1, 0.3, 1.0):
                    # presliding distance 1/s as a fraction of the travel
                    starts.append({**p, "s": 1.0 / (zs * problem.scales.travel)})
            else:
                starts.append(p)
    return starts


def effect_starts(problem: Problem, effect: str, current: dict, residual: np.ndarray) -> list[dict]:
    """Starting values of one effect's parameters from the current residual."""
    kind = problem.data.kind
    r = residual
    if effect == "viscous":
        v = problem.k / (problem.s * current["Fc"] * -math.log(0.95)) if kind == "breakaway" else problem.v
        sigma = float(np.dot(r, v) / max(np.dot(v, v), 1e-300))
        return [{"sigma": max(sigma, 0.0)}]
    if effect == "asymmetry":
        if kind == "timeseries":
            neg = problem.d < 0
            sliding = np.abs(problem.v) >= np.median(np.abs(problem.v))
            sel = neg & sliding
            shift = -float(np.median(r[sel])) if np.any(sel) else 0.0
        elif kind == "steady":
            sel = problem.v < 0
            shift = -float(np.median(r[sel])) if np.any(sel) else 0.0
        else:
            sel = problem.direction < 0
            shift = float(np.median(r[sel])) if np.any(sel) else 0.0
        Fc_neg = max(current["Fc"] + shift, 1e-3 * current["Fc"])
        Fs_neg = max(current["Fs"] + shift, Fc_neg)
        return [{"Fc_neg": Fc_neg, "Fs_neg": Fs_neg},
                {"Fc_neg": current["Fc"], "Fs_neg": current["Fs"]}]
    if effect == "offset":
        return [{"F_offset": float(np.median(r))}]
    if effect == "drift":
        basis = (problem.t - problem.t[0]) * (problem.measured - r)
        alpha = float(np.dot(r, basis) / max(np.dot(basis, basis), 1e-300))
        lo, hi = problem.bounds()[0][-1], problem.bounds()[1][-1]
        return [{"alpha": float(np.clip(alpha, 0.9 * lo, 0.9 * hi))}]
    if effect == "inertia":
        a = problem.a if kind == "timeseries" else problem.k**2
        m = float(np.dot(r, a) / max(np.dot(a, a), 1e-300))
        if kind == "breakaway":
            F_hat = current["Fc"] + (current["Fs"] - current["Fc"]) / 2
            m *= problem.s * F_hat**2 * 0.95 * (-math.log(0.95)) ** 3
        return [{"m_e": max(m, 0.0)}]
    if effect == "ripple":
        return _ripple_starts(problem, r)
    if effect == "lag":
        char_time = problem.scales.speed / max(problem.scales.accel, 1e-300)
        return [{"tau": float(tau)} for tau in char_time * np.array([0.003, 0.01, 0.03, 0.1, 0.3])]
    if effect == "backlash":
        travel = problem.scales.travel
        presliding = 1.0 / current["s"]
        plays = np.concatenate([travel * np.array([0.003, 0.01, 0.03, 0.1]),
                                presliding * np.array([0.3, 1.0, 3.0])])
        plays = plays[plays < travel / 2]
        return [{"play": float(b)} for b in plays]
    if effect == "dwell":
        positive = problem.dwell[problem.dwell > 0]
        scale = float(np.median(positive)) if positive.size else 1.0
        return [{"zeta": z, "tau_d": scale * f} for z in (0.1, 0.5) for f in (0.1, 1.0, 10.0)]
    raise ValueError(f"unknown effect {effect!r}")


def _ripple_starts(problem: Problem, r):
    """Wavelengths of the strongest periodogram peaks of the residual against x."""
    x = problem.x
    travel, step = problem.scales.travel, problem.scales.step
    wavelengths = np.geomspace(max(4 * step, travel / 2000), travel / 1.5, 600)
    omega = 2 * np.pi / wavelengths
    # subsample long records: the periodogram's cost is n × frequencies
    stride = max(1, x.size // 4000)
    power = lombscargle(x[::stride], r[::stride] - r.mean(), omega)
    starts = []
    for idx in np.argsort(power)[::-1][:40]:
        lam = wavelengths[idx]
        if any(abs(math.log(lam / s["wavelength"])) < 0.05 for s in starts):
            continue
        phase = 2 * np.pi * x / lam
        basis = np.column_stack([np.sin(phase), np.cos(phase)])
        (c_sin, c_cos), *_ = np.linalg.lstsq(basis, r, rcond=None)
        starts.append({"A": float(math.hypot(c_sin, c_cos)), "wavelength": float(lam),
                       "phase": float(math.atan2(c_cos, c_sin))})
        if len(starts) == 3:
            break
    return starts


# ---------------------------------------------------------------------------------
# the fit
# ---------------------------------------------------------------------------------


def _cost(problem, params, rows):
    r = problem.predict(params)[rows] - problem.measured[rows]
    value = float(np.dot(r, r))
    return value if math.isfinite(value) else math.inf


def _solve(problem, theta0, rows, max_nfev):
    lo, hi = problem.bounds()
    theta0 = np.clip(theta0, lo, hi)
    # keep the start strictly inside the bounds: trf needs an interior point
    span = hi - lo
    theta0 = np.clip(theta0, lo + 1e-9 * span, hi - 1e-9 * span)

    def residual(theta):
        r = problem.predict(problem.to_params(theta))[rows] - problem.measured[rows]
        return np.where(np.isfinite(r), r, 1e6 * problem.scales.force)

    return least_squares(residual, theta0, bounds=(lo, hi), method="trf", x_scale="jac",
                         max_nfev=max_nfev)


def _stderr(problem, result, n):
    names = problem.names
    p = len(names)
    dof = max(n - p, 1)
    s2 = 2 * result.cost / dof
    J = result.jac
    try:
        cov = np.linalg.pinv(J.T @ J) * s2
    except np.linalg.LinAlgError:
        return {name: math.inf for name in names}
    # Jacobian of params with respect to θ (transforms of models.Problem)
    params = problem.to_params(result.x)
    G = np.zeros((p, p))
    for i, name in enumerate(names):
        if name in LOG_PARAMS:
            G[i, i] = params[name]
        else:
            G[i, i] = 1.0
    for level, base in (("Fs", "Fc"), ("Fs_neg", "Fc_neg")):
        if level in names:
            G[names.index(level), names.index(base)] = 1.0
    cov_p = G @ cov @ G.T
    # a direction the data do not determine shows up as a (near) zero singular value
    sv = np.linalg.svd(J, compute_uv=False)
    rank_deficient = sv.size == 0 or sv[-1] < 1e-10 * sv[0]
    out = {}
    for i, name in enumerate(names):
        value = math.sqrt(max(cov_p[i, i], 0.0))
        out[name] = math.inf if (rank_deficient and value == 0.0) else value
    return out


def fit_model(data: Dataset, effects=(), starts=None, rows=None, max_nfev=None,
              screen=3, fixed=None) -> FitResult:
    """Fit the model with ``effects`` to ``data`` by bounded least squares.

    Parameters
    ----------
    data : Dataset
        Parsed measurement.
    effects : sequence of str, optional
        Effects of §7 added to the base model.
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

    Returns
    -------
    FitResult
    """
    problem = Problem(data, tuple(effects), dict(fixed or {}))
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
    r = problem.measured[rows] - prediction[rows]
    rss = float(np.dot(r, r))
    stderr = {**_stderr(problem, best, n), **{name: 0.0 for name in problem.fixed}}
    return FitResult(tuple(effects), params, stderr,
                     math.sqrt(rss / n), bic(rss, n, len(problem.names)), n, prediction,
                     problem)


def refit(data: Dataset, fit: FitResult, rows=None, max_nfev=None) -> FitResult:
    """Fit the same model again from ``fit``'s parameters (e.g. on other rows)."""
    return fit_model(data, fit.effects, starts=[fit.params], rows=rows, max_nfev=max_nfev,
                     screen=1)


def best_base_starts(data: Dataset, count: int = 4) -> list[dict]:
    """The ``count`` base starting points of :func:`base_starts` with the lowest cost."""
    problem = Problem(data)
    starts = base_starts(problem)
    rows = np.arange(data.n)
    costs = [_cost(problem, s, rows) for s in starts]
    return [starts[i] for i in np.argsort(costs)[:count]]


def fit_with_effect(data: Dataset, current: FitResult, effect: str, rows=None,
                    screen=2, restarts=()) -> FitResult:
    """Add ``effect`` to ``current``'s model and fit everything again.

    Starts: ``current``'s parameters with the effect's values read off the residual,
    and the same effect values on each of ``restarts`` (base parameter sets, e.g.
    :func:`best_base_starts`), so a fit is not trapped in the current model's basin.
    """
    problem = Problem(data, current.effects + (effect,))
    extras = effect_starts(problem, effect, current.params, current.residual())
    starts = []
    for origin in (current.params, *restarts):
        starts.extend({**current.params, **origin, **extra} for extra in extras)
    if effect in PROFILED:
        return _profiled_fit(data, problem.effects, PROFILED[effect], starts, rows)
    return fit_model(data, problem.effects, starts=starts, rows=rows, screen=screen)


#: Effects whose parameter switches the model discretely (the play engages or not):
#: finite differences cannot move it, so it is profiled on its grid of starts and 0.
PROFILED = {"backlash": "play"}


def _profiled_fit(data, effects, name, starts, rows):
    """Fit with ``name`` held at each start's value (and 0), then free from the best."""
    by_value = {}
    for start in starts:
        by_value.setdefault(start[name], []).append(start)
    zero = {**starts[0], name: 0.0}
    by_value.setdefault(0.0, [zero])
    best = None
    n_free = len(Problem(data, effects).names) - 1
    for value, group in by_value.items():
        fit = fit_model(data, effects, starts=group, rows=rows, screen=1, fixed={name: value},
                        max_nfev=8 * (n_free + 1))
        if best is None or fit.bic < best.bic:
            best = fit
    free = fit_model(data, effects, starts=[best.params], rows=rows, screen=1)
    return free if free.bic <= best.bic else _evaluated_at(data, effects, best.params, rows)


def _evaluated_at(data, effects, params, rows):
    """The model with every parameter free, evaluated at ``params`` without moving them
    (least_squares stops after its first evaluation), so each parameter gets its
    standard error from the Jacobian there."""
    return fit_model(data, effects, starts=[params], rows=rows, screen=1, max_nfev=1)


__all__ = ["FitError", "FitResult", "base_starts", "best_base_starts", "bic", "effect_starts",
           "fit_model", "fit_with_effect", "refit"]
