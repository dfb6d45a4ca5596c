"""``beyond-data``: a parameter that describes a part of the friction
curve the data never show is not determined, whatever its standard error says, and
the warning gives the bound the data do set.

- The record never reaches gross sliding (a presliding or creep record): Fc, Fs, V and
  δ describe the sliding curve; the largest force held without sliding is a lower
  bound on Fs.
- Fs above every measured force (the Stribeck peak is an extrapolation), or below a
  force the data hold without gross sliding (a contradiction the fit was forced into).
- The Stribeck drop of V and δ lies entirely below the slowest speed at which the data
  show the curve (then Fs is an extrapolation too) or above the fastest (then Fc is);
  or there is no drop: Fs sits on Fs = Fc, and V, δ describe nothing.
- The drop's shape δ is not determined: the peak Fs at rest is an extrapolation
  through that shape, and V with it.
"""

from __future__ import annotations

import math

import numpy as np

from ..fitting import FitResult
from . import warning

#: The drop of g (E2) is seen where exp(−(v/V)^δ) lies between these fractions.
DROP_SEEN = (0.1, 0.9)
#: Fs is above every measured force when it exceeds the largest by this share ...
ABOVE_SHARE = 0.05
#: ... and by this many noise floors.
ABOVE_NOISE = 3.0
#: Fc is beyond the data when a concave viscous term's extrapolation below the slowest
#: speed shown makes up more than this share of the friction there.
EXTRAPOLATED_SHARE = 0.25
#: The peak Fs is an extrapolation through the drop's shape: with δ's relative standard
#: error above this, the peak and V are not determined.
SHAPE_RELATIVE_ERROR = 0.5
#: The levels of each direction and the parameters of their drop.
LEVELS = (("Fc", "Fs"), ("Fc_neg", "Fs_neg"))


def _drop_speeds(V: float, delta: float) -> tuple[float, float]:
    """Speeds [m/s] where the Stribeck term exp(−(v/V)^δ) has fallen to 0.9 and 0.1."""
    high, low = DROP_SEEN[1], DROP_SEEN[0]
    return V * (-math.log(high)) ** (1 / delta), V * (-math.log(low)) ** (1 / delta)


#: How δ came out not determined (``Assessment.why``), in words.
_WHY = {"at-bound": "at the bound of its range", "flat": "on which the fit does not depend",
        "artefact": "with a standard error too small to be real",
        "relative": "with a standard error larger than itself"}


def _shape_unknown(fit: FitResult) -> str | None:
    """How δ is not determined, where it is not (a relative standard error above
    :data:`SHAPE_RELATIVE_ERROR` counts: the peak extrapolates through the shape)."""
    a = fit.assessment
    value = fit.params.get("delta")
    if value is None or a.why.get("delta") == "fixed":
        return None
    se = a.stderr.get("delta")
    why = a.why.get("delta")
    if why is not None or se is None:
        if (why or "").startswith("correlated:"):
            return f"δ = {value:.3g}, tied to {why.split(':', 1)[1]}"
        return f"δ = {value:.3g}, {_WHY.get(why, 'without a standard error')}"
    if se > SHAPE_RELATIVE_ERROR * abs(value):
        return f"δ = {value:.3g} ± {se:.2g}"
    return None


def beyond_data(fit: FitResult, noise: float, known=None) -> dict[str, str]:
    """The parameters of ``fit`` the data cannot hold, each with the sentence that says
    why and gives the bound the data set (first reason per parameter; ``known``
    sentences, e.g. of a drop the data do not resolve, come first)."""
    pb, p = fit.problem, fit.params
    unit = pb.data.unit("N")
    speed_unit = pb.data.unit("m/s")
    known = known or {}
    found: dict[str, str] = dict(known)

    def add(names, text):
        for name in names:
            if name in p and name not in found and (name not in pb.fixed or name in known):
                found[name] = text

    speeds = pb.curve_speeds(p)
    held = pb.held_force(p)
    top = float(np.max(np.abs(pb.measured)))
    if speeds.size == 0:
        bound = max(held) if held is not None else top
        z = float(np.max(pb.presliding_fraction(p))) if hasattr(pb, "presliding_fraction") \
            else math.nan
        add(("Fc", "Fs", "V", "delta", "Fc_neg", "Fs_neg"), (
            f"the record never reaches gross sliding (the fitted presliding fraction z "
            f"reaches {z:.2g} of 1): the sliding curve is never shown; the largest force "
            f"held without sliding, {bound:.4g} {unit}, is a lower bound on Fs"))
        return found

    asymmetric = "Fs_neg" in p
    slowest, fastest = float(np.min(speeds)), float(np.max(speeds))
    if "n" in p and p["n"] < 1.0:
        # a concave σ·|v|ⁿ rises fastest below the slowest speed the data show: what it
        # adds there is an extrapolation of the curve's form. Where that is a small part of
        # the level, Fc is still a result (its standard error carries the trade with n);
        # where it is a large part, Fc is the form's guess, and the data set a bound
        below = p["sigma"] * slowest ** p["n"]
        at_slowest = p["Fc"] + below
        if below > ABOVE_NOISE * noise and below > EXTRAPOLATED_SHARE * at_slowest:
            add(("Fc", "Fc_neg"), (
                f"the curved viscous term σ·|v|^{p['n']:.2g} adds {below:.4g} {unit} between "
                f"rest and the slowest speed at which the data show the curve "
                f"({slowest:.3g} {speed_unit}), a part of the curve they never show: the "
                f"friction there, {at_slowest:.4g} {unit}, is an upper bound on Fc"))
    shape = _shape_unknown(fit)
    for (low, level), way in zip(LEVELS, (0, 1)):
        if level not in p:
            continue
        Fs, Fc = p[level], p[low]
        # without asymmetry one level holds both ways
        bound = None if held is None else (held[way] if asymmetric else max(held))
        # the fitted curve's friction at the slowest speed the data show it at
        at_slowest = Fc + (Fs - Fc) * math.exp(-(slowest / p["V"]) ** p["delta"])
        if Fs > top * (1 + ABOVE_SHARE) and Fs > top + ABOVE_NOISE * noise:
            # a force held without sliding bounds Fs from below; else the curve's own
            # value at the slowest speed it is shown at (the largest force of a steady
            # curve sits at its fastest speed and bounds nothing)
            floor = bound if bound is not None else at_slowest
            add((level,), (
                f"{level} = {Fs:.4g} {unit} lies above every force in the file (the largest is "
                f"{top:.4g} {unit}): the Stribeck peak is an extrapolation; the data set "
                f"only {level} ≥ {floor:.4g} {unit}"))
        if bound is not None and Fs < bound - ABOVE_NOISE * noise:
            add((level,), (
                f"{level} = {Fs:.4g} {unit} is below {bound:.4g} {unit}, a force the data hold "
                f"without gross sliding, which is a lower bound on {level}"))
        if fit.assessment.bound.get(level) == "lower" or Fs <= Fc:
            add(("V", "delta"), (
                f"{level} sits on {level} = {low} (no Stribeck drop in the data): V and δ "
                f"describe a drop that is not there"))
            continue
        begins, ends = _drop_speeds(p["V"], p["delta"])
        if shape:
            add((level, "V", "delta"), (
                f"the shape of the Stribeck drop is not determined ({shape}), so neither is "
                f"where it falls (V) nor the peak {level} it extrapolates to at rest; the "
                f"friction at the slowest sliding speed, {at_slowest:.4g} {unit}, is a lower "
                f"bound on {level}"))
        if ends < slowest:
            add((level, "V", "delta"), (
                f"the Stribeck drop of V = {p['V']:.3g} {speed_unit} and δ = {p['delta']:.3g} is over by "
                f"{ends:.3g} {speed_unit}, below the slowest speed at which the data show "
                f"the curve ({slowest:.3g} {speed_unit}): the data show only the level "
                f"{low}; the friction there, {at_slowest:.4g} {unit}, is a lower bound on "
                f"{level}"))
        elif begins > fastest:
            add((low, "V", "delta"), (
                f"the Stribeck drop of V = {p['V']:.3g} {speed_unit} and δ = {p['delta']:.3g} begins at "
                f"{begins:.3g} {speed_unit}, above the fastest speed at which the data show "
                f"the curve ({fastest:.3g} {speed_unit}): the data show only the peak "
                f"{level}, which is an upper bound on {low}"))
    return found


def mark_beyond(fit: FitResult, beyond: dict[str, str]) -> None:
    """Record in ``fit``'s assessment that the parameters of ``beyond`` are not
    determined (no standard error, reason ``beyond-data``)."""
    a = fit.assessment
    for name in beyond:
        a.stderr[name] = None
        a.determined[name] = False
        a.why[name] = "beyond-data"


def beyond_data_warnings(beyond: dict[str, str]) -> list[dict]:
    """One ``beyond-data`` warning per parameter."""
    return [warning("beyond-data", name, text) for name, text in beyond.items()]


__all__ = ["beyond_data", "beyond_data_warnings", "mark_beyond"]
