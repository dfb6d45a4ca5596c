"""Warnings about what a fit determines: ``at-bound`` and ``undetermined``, one per
parameter that is not a result. A parameter ``beyond-data`` is not determined either:
it gets an ``undetermined`` warning that points to the bound the data set."""

from __future__ import annotations

from ..fitting import FitResult
from . import warning

_WHY = {
    "flat": "moves along a flat direction of the fit",
    "relative": "has a standard error larger than its value",
    "artefact": "has a standard error below 1e-9 of its value (a numerical artefact)",
}


def fit_warnings(fit: FitResult) -> list[dict]:
    """One warning per parameter the fit does not determine, saying why."""
    out = []
    a = fit.assessment
    for name, reason in a.why.items():
        if reason is None or reason == "fixed":
            continue
        value = fit.params[name]
        if reason == "beyond-data":
            out.append(warning("undetermined", name, (
                f"{name} = {value:.4g} is not determined: it describes a part of the curve "
                f"the data never show (its beyond-data warning gives the bound they set)")))
            continue
        if reason == "at-bound":
            side = a.bound.get(name, "a")
            text = f"{name} = {value:.4g} ended on the {side} bound of its range"
            if name in ("Fs", "Fs_neg"):
                low = "Fc" if name == "Fs" else "Fc_neg"
                text += (f" ({name} = {low}): the data show no velocity weakening, so the "
                         f"Stribeck velocity and shape are not determined")
            out.append(warning("at-bound", name, text + "; it is not a result"))
            continue
        if reason.startswith("correlated:"):
            other = reason.split(":", 1)[1]
            text = (f"{name} = {value:.4g} is correlated above 0.99 with {other}: the data "
                    f"determine a combination of the two, not each")
        else:
            se = a.stderr.get(name)
            se_text = f" (± {se:.2g})" if se is not None else ""
            text = f"{name} = {value:.4g}{se_text} {_WHY[reason]}: the data do not determine it"
        out.append(warning("undetermined", name, text))
    return out


__all__ = ["fit_warnings"]
