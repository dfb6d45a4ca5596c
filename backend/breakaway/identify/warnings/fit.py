"""Warnings about what a fit determines: ``at-bound`` and ``undetermined``, one per
parameter that is not a result, its values in the data's units. A parameter
``beyond-data`` is not determined either: it gets an ``undetermined`` warning that
points to the bound the data set."""

from __future__ import annotations

from ..effects import param_spec
from ..fitting import FitResult
from . import warning

_WHY = {
    "flat": "moves along a flat direction of the fit",
    "relative": "has a standard error larger than its value",
    "artefact": "has a standard error below 1e-9 of its value (a numerical artefact)",
}


def _unit(fit: FitResult, name: str) -> str:
    """The unit of parameter ``name`` in the fit's data (rotary: N·m, rad, …), or ""."""
    unit = fit.problem.data.unit(param_spec(name, fit.effects).unit)
    return "" if unit in ("", "-") else unit


def _quantity(value: float, unit: str, spec: str = ".4g") -> str:
    return f"{value:{spec}} {unit}" if unit else f"{value:{spec}}"


def fit_warnings(fit: FitResult) -> list[dict]:
    """One warning per parameter the fit does not determine, saying why."""
    out = []
    a = fit.assessment
    for name, reason in a.why.items():
        if reason is None or reason == "fixed":
            continue
        value = fit.params[name]
        unit = _unit(fit, name)
        if reason == "beyond-data":
            out.append(warning("undetermined", name, (
                f"{name} = {_quantity(value, unit)} is not determined: it describes a part "
                f"of the curve the data never show (its beyond-data warning gives the bound "
                f"they set)")))
            continue
        if reason == "at-bound":
            side = a.bound.get(name, "a")
            text = f"{name} = {_quantity(value, unit)} ended on the {side} bound of its range"
            if name in ("Fs", "Fs_neg"):
                low = "Fc" if name == "Fs" else "Fc_neg"
                text += (f" ({name} = {low}): the data show no velocity weakening, so the "
                         f"Stribeck velocity and shape are not determined")
            out.append(warning("at-bound", name, text + "; it is not a result"))
            continue
        if reason.startswith("correlated:"):
            other = reason.split(":", 1)[1]
            c = a.correlated.get(name)
            if c is None:
                text = (f"{name} = {_quantity(value, unit)} is correlated above 0.99 with {other}: "
                        f"the data determine a combination of the two, not each")
            else:
                combined = value - c["slope"] * fit.params[other]
                sign = "+" if c["slope"] < 0 else "−"
                text = (f"{name} = {_quantity(value, unit)} moves with {other} (correlation "
                        f"r = {c['r']:+.3f}): the data determine {name} {sign} "
                        f"{abs(c['slope']):.3g}·{other} = {_quantity(combined, unit)} ± "
                        f"{_quantity(c['stderr'], unit, '.2g')}, not each")
        else:
            se = a.stderr.get(name)
            se_text = f" (± {_quantity(se, unit, '.2g')})" if se is not None else ""
            text = (f"{name} = {_quantity(value, unit)}{se_text} {_WHY[reason]}: the data do not "
                    f"determine it")
        out.append(warning("undetermined", name, text))
    return out


__all__ = ["fit_warnings"]
