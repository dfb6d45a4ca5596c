"""The identification report of a :class:`~.diagnosis.Diagnosis`."""

from __future__ import annotations

import math

from .diagnosis import Diagnosis
from .effects import param_spec
from .extent import record_extent
from .fitting import FitResult


def _clean(value):
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def units(data) -> dict[str, str]:
    """Units of the data's columns and of every parameter key, linear or rotary."""
    columns = {"F": "N", "F_ba": "N", "x": "m", "v": "m/s", "t": "s", "k": "N/s",
               "dwell": "s", "a": "m/s²"}
    return {name: data.unit(u) for name, u in columns.items()}


def model_entry(fit: FitResult) -> dict:
    """``params``, ``stderr``, ``determined``, ``rmse``, ``bic`` of one model."""
    return {"params": {k: _clean(v) for k, v in fit.params.items()},
            "stderr": {k: _clean(fit.stderr.get(k)) for k in fit.params},
            "determined": {k: bool(fit.determined.get(k, False)) for k in fit.params},
            "rmse": _clean(fit.rmse), "bic": _clean(fit.bic)}


def covariance_entry(fit: FitResult) -> dict:
    """The covariance of the parameters that have a standard error: ``names`` and
    ``matrix`` (rows and columns in that order, in the parameters' units). Its diagonal
    is the reported standard errors squared; the correlations are the fit's."""
    a = fit.assessment
    names = [name for name in a.names if _clean(fit.stderr.get(name)) is not None]
    index = [a.names.index(name) for name in names]
    se = [float(fit.stderr[name]) for name in names]
    matrix = []
    for i, row in zip(index, se):
        line = []
        for j, column in zip(index, se):
            rho = 1.0 if i == j else float(a.correlation[i, j])
            line.append(row * column * (rho if math.isfinite(rho) else 0.0))
        matrix.append(line)
    return {"names": names, "matrix": matrix}


def correlated(fit: FitResult) -> dict:
    """The parameters of ``fit`` not determined only through a correlation, each with
    what the data do determine (:class:`~.identifiability.Assessment` ``correlated``)."""
    a = fit.assessment
    return {name: {"with": c["with"], "r": _clean(c["r"]), "slope": _clean(c["slope"]),
                   "stderr": _clean(c["stderr"])}
            for name, c in a.correlated.items() if (a.why.get(name) or "").startswith("correlated:")}


def parameter_units(data, names, effects=()) -> dict[str, str]:
    """Units of the parameter keys ``names`` of a model with ``effects``."""
    return {name: data.unit(param_spec(name, effects).unit) for name in names}


def report(diagnosis: Diagnosis) -> dict:
    """The identification report as a JSON-ready dict.

    Besides the documented keys: each step's held-out error ``heldout``; ``units`` (of the
    columns and of every parameter, linear or rotary); ``correlated`` (of the base and
    the final model: the parameters not determined only through a correlation, and the
    combination the data determine, :func:`correlated`); ``noise_method`` (how the floor
    was estimated); ``screened_rows`` (rows of the blocks the candidates were screened
    on, 0 when every row was used) and ``seconds`` (wall time); what an export of the
    model needs beyond ``final.params``: ``t_0`` (timeseries: the first sample's time,
    where ``drift`` refers to) and ``s`` (breakaway: the presliding scale E13 used);
    ``final.covariance`` (:func:`covariance_entry`) and ``extent`` (what the record
    spans, :func:`~.extent.record_extent`), which a plan of the next experiment starts
    from.
    """
    d = diagnosis
    return {
        "kind": d.data.kind,
        "n": d.data.n,
        "noise_floor": _clean(d.noise.value),
        "noise_method": d.noise.method,
        "base": model_entry(d.base),
        "steps": [{"effect": s.effect, **model_entry(s.fit), "evidence": s.evidence,
                   "heldout": _clean(s.heldout)} for s in d.steps],
        "effects": d.effects,
        "final": {**model_entry(d.final), "covariance": covariance_entry(d.final)},
        "error_before": _clean(d.base.rmse),
        "error_after": _clean(d.final.rmse),
        "heldout": {"before": _clean(d.heldout_before), "after": _clean(d.heldout_after)},
        "input_floor": _clean(d.input_floor),
        "residual_white": bool(d.white),
        "unexplained": bool(d.unexplained),
        "warnings": list(d.warnings),
        "residual_structure": list(d.structure),
        "candidates": {e: {"rmse": _clean(c.rmse), "bic": _clean(c.bic),
                           "heldout": _clean(c.heldout), "accepted": bool(c.accepted),
                           "reason": c.reason}
                       for e, c in d.candidates.items()},
        "correlated": {"base": correlated(d.base), "final": correlated(d.final)},
        "units": {**units(d.data),
                  **parameter_units(d.data, list(d.base.params) + list(d.final.params),
                                   d.final.effects)},
        **({"derivatives": d.base.problem.derivatives.entry()}
           if d.data.kind == "timeseries" else {}),
        "extent": record_extent(d.final),
        "screened_rows": d.screened_rows,
        "seconds": round(d.seconds, 3),
        **_context(d.data),
    }


def _context(data) -> dict:
    """``t_0`` of a time series, ``s`` of break-away data (see :func:`report`)."""
    if data.kind == "timeseries":
        return {"t_0": float(data.columns["t"][0])}
    if data.kind == "breakaway":
        return {"s": data.meta_float("s", 1.0)}
    return {}


__all__ = ["covariance_entry", "model_entry", "report", "units"]
