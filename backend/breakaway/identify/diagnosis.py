"""The residual → effect loop and the identification report (MODEL.md §8).

1. Fit the base model; estimate the noise floor without any model.
2. While the residual is not white: fit every remaining candidate effect of §7 (all
   parameters refitted, starts taken from the residual; every round tries them all,
   since a large effect can mask a small one), and accept the one with the
   lowest BIC among those that pass every gate — the BIC falls by at least
   :data:`MIN_BIC_DROP`, the error falls by a share of the structured residual that an
   effect would have to explain (:data:`MIN_EXCESS_EXPLAINED`), and the held-out error
   falls too. BIC's ``ln n`` per parameter settles nested ties (``offset`` before
   ``asymmetry``).
3. Drop any accepted effect that later ones made redundant (backward check).
4. ``residual_white`` compares the final residual with the noise floor and with white
   noise; ``unexplained`` is set when clear structure is left that no candidate explains.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from threadpoolctl import threadpool_limits

from .csvdata import Dataset
from .effects import candidates
from .fitting import FitResult, best_base_starts, fit_model, fit_with_effect, refit
from .residuals import is_white, noise_floor, signature

#: A BIC drop of 10 is "very strong" evidence (Kass & Raftery 1995).
MIN_BIC_DROP = 10.0
#: An accepted effect removes at least this share of the residual variance above the
#: noise floor (an effect that is there removes nearly all of its own part).
MIN_EXCESS_EXPLAINED = 0.25
#: ... and at least this relative share of the RMSE.
MIN_RMSE_GAIN = 0.01
#: Structure is "clear" when the final RMSE exceeds the noise floor by this factor.
UNEXPLAINED_RATIO = 1.3


@dataclass
class Step:
    effect: str
    fit: FitResult
    evidence: str
    heldout: float


@dataclass
class Diagnosis:
    """Everything the report and the explorer's data panel show."""

    data: Dataset
    noise: float
    base: FitResult
    final: FitResult
    steps: list[Step]
    heldout_before: float
    heldout_after: float
    white: bool
    unexplained: bool
    tried: dict = field(default_factory=dict)  # effect -> (rmse, bic, heldout) of the last round
    seconds: float = 0.0

    @property
    def effects(self) -> list[str]:
        return list(self.final.effects)


def heldout_rows(data: Dataset):
    """Training rows and held-out rows (§8: the last 20 % of a timeseries, every 5th
    row otherwise)."""
    n = data.n
    idx = np.arange(n)
    if data.kind == "timeseries":
        cut = int(round(0.8 * n))
        return idx[:cut], idx[cut:]
    test = idx[4::5]
    return np.setdiff1d(idx, test), test


def _heldout_error(data: Dataset, fit: FitResult, train, test) -> float:
    trained = refit(data, fit, rows=train)
    r = trained.problem.measured[test] - trained.prediction[test]
    return math.sqrt(float(np.mean(r**2)))


def _passes(current: FitResult, trial: FitResult, noise: float) -> bool:
    if not trial.bic <= current.bic - MIN_BIC_DROP:
        return False
    if trial.rmse > (1 - MIN_RMSE_GAIN) * current.rmse:
        return False
    excess = current.rmse**2 - noise**2
    if excess <= 0:
        return False
    return (current.rmse**2 - trial.rmse**2) >= MIN_EXCESS_EXPLAINED * excess


def diagnose(data: Dataset, progress=None) -> Diagnosis:
    """Fit, trace the residual to missing effects, and refit (see module docstring).

    Parameters
    ----------
    data : Dataset
    progress : callable, optional
        Called as ``progress(fraction, message)`` as the work advances; an exception it
        raises ends the diagnosis (how a job is cancelled).
    """
    # one BLAS thread: the Jacobians are tall and thin, threads only contend
    with threadpool_limits(limits=1, user_api="blas"):
        return _diagnose(data, progress)


def _diagnose(data: Dataset, progress) -> Diagnosis:
    started = time.perf_counter()
    report = progress or (lambda fraction, message: None)
    report(0.0, "fitting the base model")
    base = fit_model(data)
    noise = noise_floor(base.problem)
    train, test = heldout_rows(data)
    current, current_heldout = base, _heldout_error(data, base, train, test)
    heldout_before = current_heldout
    restarts = best_base_starts(data)
    remaining = candidates(data.kind, data.columns)
    total = max(len(remaining), 1)
    steps: list[Step] = []
    tried = {}
    while remaining and not is_white(current.residual(), current.problem, noise):
        trials = {}
        for i, effect in enumerate(remaining):
            report(len(steps) / total + i / total**2, f"trying {effect}")
            try:
                trials[effect] = fit_with_effect(data, current, effect, restarts=restarts)
            except ValueError:
                continue
        tried = {e: (f.rmse, f.bic, None) for e, f in trials.items()}
        chosen = None
        for effect in sorted(trials, key=lambda e: trials[e].bic):
            trial = trials[effect]
            if not _passes(current, trial, noise):
                continue
            trial_heldout = _heldout_error(data, trial, train, test)
            tried[effect] = (trial.rmse, trial.bic, trial_heldout)
            if trial_heldout < current_heldout:
                chosen = effect, trial, trial_heldout
                break
        if chosen is None:
            break
        effect, trial, trial_heldout = chosen
        evidence = (signature(effect, current.problem, current.residual(), trial.params)
                    + f"; with it the RMSE falls from {current.rmse:.4g} to {trial.rmse:.4g} N"
                    + f" and the BIC by {current.bic - trial.bic:.1f}")
        steps.append(Step(effect, trial, evidence, trial_heldout))
        current, current_heldout = trial, trial_heldout
        remaining = [e for e in remaining if e != effect]
        report(len(steps) / total, f"accepted {effect}")
    current, current_heldout = _backward(data, current, current_heldout, train, test)
    white = is_white(current.residual(), current.problem, noise)
    unexplained = (not white) and current.rmse > UNEXPLAINED_RATIO * noise
    report(1.0, "done")
    return Diagnosis(data, noise, base, current, steps, heldout_before, current_heldout,
                     white, unexplained, tried, time.perf_counter() - started)


def _backward(data, current, current_heldout, train, test):
    """Drop accepted effects that the others have made redundant (parsimony)."""
    changed = True
    while changed and len(current.effects) > 1:
        changed = False
        for effect in current.effects:
            others = tuple(e for e in current.effects if e != effect)
            reduced = fit_model(data, others, starts=[current.params], screen=1)
            if reduced.bic <= current.bic + MIN_BIC_DROP / 2:
                current = reduced
                current_heldout = _heldout_error(data, reduced, train, test)
                changed = True
                break
    return current, current_heldout


# ---------------------------------------------------------------------------------
# the report
# ---------------------------------------------------------------------------------


def _clean(value):
    value = float(value)
    return value if math.isfinite(value) else None


def _model_entry(fit: FitResult) -> dict:
    return {"params": {k: _clean(v) for k, v in fit.params.items()},
            "stderr": {k: _clean(v) for k, v in fit.stderr.items()},
            "rmse": _clean(fit.rmse), "bic": _clean(fit.bic)}


def report(diagnosis: Diagnosis) -> dict:
    """The §8 identification report as a JSON-ready dict.

    Besides the §8 keys, each model entry carries ``stderr`` (standard errors of its
    parameters, ``null`` where the data do not determine one), each step its held-out
    error ``heldout``, and the report carries
    ``candidates`` (each effect tried in the last round against the model it would have
    extended: its RMSE and BIC, and its held-out error where it passed the other gates)
    and ``seconds`` (wall time of the diagnosis).
    """
    d = diagnosis
    return {
        "kind": d.data.kind,
        "n": d.data.n,
        "noise_floor": _clean(d.noise),
        "base": _model_entry(d.base),
        "steps": [{"effect": s.effect, **_model_entry(s.fit), "evidence": s.evidence,
                   "heldout": _clean(s.heldout)} for s in d.steps],
        "effects": d.effects,
        "final": _model_entry(d.final),
        "error_before": _clean(d.base.rmse),
        "error_after": _clean(d.final.rmse),
        "heldout": {"before": _clean(d.heldout_before), "after": _clean(d.heldout_after)},
        "residual_white": bool(d.white),
        "unexplained": bool(d.unexplained),
        "candidates": {e: {"rmse": _clean(rmse), "bic": _clean(b),
                           "heldout": None if h is None else _clean(h)}
                       for e, (rmse, b, h) in d.tried.items()},
        "seconds": round(d.seconds, 3),
    }
