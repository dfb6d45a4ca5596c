"""The fitted model of an identification report, read and checked for export.

What leaves the tool is the friction that acts on the body: the steady curve (E2)
with the accepted effects that change it (``viscous``, ``viscous-power``,
``asymmetry``, ``drift``) and the presliding law (E6') with its reversal memory. The
other effects describe the measurement (``offset``, ``inertia``, ``ripple``,
``detection``) or need more than a position to evaluate (``lag``: a filter state on
the velocity; ``backlash``: the play's state; ``dwell``: the time at rest before a
break-away); they are named in the export as left out, with the reason.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..identify.effects import unit_of
from ..params import check_positive, check_stribeck

#: The effects that act on the body, with the report keys each needs.
BODY_EFFECTS: dict[str, tuple[str, ...]] = {
    "viscous": ("sigma",),
    "viscous-power": ("sigma", "n"),
    "asymmetry": ("Fc_neg", "Fs_neg"),
    "drift": ("alpha",),
}

#: Why an accepted effect is not part of the exported friction.
LEFT_OUT: dict[str, str] = {
    "offset": "a bias of the force sensor, not friction",
    "inertia": "the measured force's inertial part m_e·a, not friction",
    "ripple": "a position-dependent force of the measurement set-up",
    "detection": "a delay of the rig's break-away detection, not friction",
    "lag": "frictional lag needs a filter state of the velocity; not exported",
    "backlash": "the play's state needs the drive-side position; not exported",
    "dwell": "stiction rising with the dwell time before a break-away; not exported",
}

#: SI units of the linear quantities; rotary data turn them (N → N·m, m → rad, …).
_SI_UNITS = {"F": "N", "x": "m", "v": "m/s", "t": "s", "Fc": "N", "Fs": "N", "V": "m/s",
             "delta": "", "s": "1/m", "sigma": "N·s/m", "n": "", "Fc_neg": "N",
             "Fs_neg": "N", "alpha": "1/s", "t_0": "s"}


class ReportError(ValueError):
    """The report cannot be exported; ``path`` locates the offending key."""

    def __init__(self, message: str, path: tuple = ()):
        super().__init__(message)
        self.path = path


@dataclass(frozen=True)
class ExportModel:
    """The friction to export: every parameter, in the report's units.

    Effects not accepted take their neutral values: σ = 0, n = 1, the negative
    levels equal to the positive ones, α = 0 (t_0 then plays no part).
    """

    kind: str
    Fc: float
    Fs: float
    V: float
    delta: float
    s: float
    sigma: float = 0.0
    n: float = 1.0
    Fc_neg: float | None = None
    Fs_neg: float | None = None
    alpha: float = 0.0
    t_0: float = 0.0
    effects: tuple[str, ...] = ()
    left_out: tuple[tuple[str, str], ...] = ()
    units: dict[str, str] = field(default_factory=dict)

    @property
    def levels_negative(self) -> tuple[float, float]:
        """(Fc, Fs) where the motion is negative."""
        return (self.Fc if self.Fc_neg is None else self.Fc_neg,
                self.Fs if self.Fs_neg is None else self.Fs_neg)

    @property
    def rotary(self) -> bool:
        return self.units.get("x") == "rad"

    def params(self) -> dict[str, float]:
        """The parameters the exported code uses, by report key."""
        Fc_neg, Fs_neg = self.levels_negative
        return {"Fc": self.Fc, "Fs": self.Fs, "V": self.V, "delta": self.delta, "s": self.s,
                "sigma": self.sigma, "n": self.n, "Fc_neg": Fc_neg, "Fs_neg": Fs_neg,
                "alpha": self.alpha, "t_0": self.t_0}


def _number(value, path) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ReportError(f"report's {'.'.join(path)} must be a number, got {value!r}", path)
    if not math.isfinite(value):
        raise ReportError(f"report's {'.'.join(path)} must be finite, got {value}", path)
    return float(value)


def _units(report: dict) -> dict[str, str]:
    given = report.get("units")
    given = given if isinstance(given, dict) else {}
    rotary = given.get("x") in ("rad", "deg") or given.get("F") == "N·m"
    units = {key: unit_of(unit, rotary) for key, unit in _SI_UNITS.items()}
    units.update({key: value for key, value in given.items()
                  if key in units and isinstance(value, str)})
    return units


def model_from_report(report, s: float | None = None, t_0: float | None = None) -> ExportModel:
    """Read the fitted model of a report (``final.params`` and ``effects``).

    Parameters
    ----------
    report : dict
        The report (``breakaway fit --json``, ``POST /api/fit``).
    s : float, optional
        Presliding scale [1/m] where the report has none (a ``steady`` fit does not
        determine it) or to replace it.
    t_0 : float, optional
        Start time [s] of the drift (the report's ``t_0``: its first sample's time).

    Raises
    ------
    ReportError
        Naming what is missing or wrong.
    """
    if not isinstance(report, dict):
        raise ReportError("a report must be a JSON object (the output of breakaway fit --json)")
    final = report.get("final")
    if not isinstance(final, dict) or not isinstance(final.get("params"), dict):
        raise ReportError("report has no final.params: not a breakaway fit report "
                          "(breakaway fit FILE --json)", ("final", "params"))
    params = final["params"]
    effects = report.get("effects")
    if not isinstance(effects, list) or not all(isinstance(e, str) for e in effects):
        raise ReportError("report has no effects list (names of the accepted effects)",
                          ("effects",))
    if "viscous" in effects and "viscous-power" in effects:
        raise ReportError("report accepts both viscous and viscous-power, which exclude "
                          "each other (viscous is viscous-power with n = 1)", ("effects",))
    values = {}
    for key in ("Fc", "Fs", "V", "delta"):
        if key not in params:
            raise ReportError(f"report's final.params lack {key}", ("final", "params", key))
        values[key] = _number(params[key], ("final", "params", key))
    exported = [e for e in effects if e in BODY_EFFECTS]
    for effect in exported:
        for key in BODY_EFFECTS[effect]:
            if key not in params:
                raise ReportError(f"effect {effect} is accepted but report's final.params "
                                  f"lack {key}", ("final", "params", key))
            values[key] = _number(params[key], ("final", "params", key))
    if s is None:
        s = params.get("s", report.get("s"))
        if s is None:
            raise ReportError(f"report ({report.get('kind', 'unknown kind')}) has no "
                              "presliding scale s (only a timeseries fit determines it): "
                              "give one (--s, or s in the request)", ("final", "params", "s"))
        s = _number(s, ("final", "params", "s"))
    if "drift" in exported:
        if t_0 is None:
            t_0 = report.get("t_0")
            if t_0 is None:
                raise ReportError("effect drift needs t_0, the time its level refers to "
                                  "(the first sample's): the report has none; give one "
                                  "(--t0, or t_0 in the request)", ("t_0",))
        t_0 = _number(t_0, ("t_0",))
    try:
        check_stribeck(values["Fc"], values["Fs"], values["V"], values["delta"],
                       values.get("sigma", 0.0))
        check_positive(s=s)
        if "asymmetry" in exported:
            check_positive(Fc_neg=values["Fc_neg"])
            if values["Fs_neg"] < values["Fc_neg"]:
                raise ValueError(f"Fs_neg must be >= Fc_neg, got Fs_neg={values['Fs_neg']} "
                                 f"< Fc_neg={values['Fc_neg']}")
        if "viscous-power" in exported:
            check_positive(n=values["n"])
    except ValueError as err:
        name = str(err).split()[0]
        raise ReportError(f"report's final.params: {err}", ("final", "params", name)) from None
    left_out = tuple((e, LEFT_OUT.get(e, "not an effect this version knows; not exported"))
                     for e in effects if e not in BODY_EFFECTS)
    return ExportModel(kind=str(report.get("kind", "unknown")), s=float(s),
                       t_0=float(t_0 or 0.0), effects=tuple(exported), left_out=left_out,
                       units=_units(report), **values)


__all__ = ["BODY_EFFECTS", "ExportModel", "LEFT_OUT", "ReportError", "model_from_report"]
