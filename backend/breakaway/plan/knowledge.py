"""What is known before the next experiment: the parameters' values, what the data
determine and how well (the covariance), what they leave open and over which range,
the noise of a measurement, and the record's units and extent.

Two sources: an identification report (``breakaway fit --json``), or a set of
parameters (the explorer's), which no data stand behind: then nothing is determined
and the plan is made at those values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..identify.csvdata.dataset import unit_of
from ..params import DEFAULTS, check_f_hat, check_fraction, check_stribeck
from .curve import LOG_PARAMETERS, PARAMETERS, symbol

#: The range an open δ is taken over (the shapes friction curves show: from a slow,
#: stretched fall to a Gaussian one).
DELTA_RANGE = (0.5, 2.0)
#: An open V below the slowest speed at which the data show the curve is taken from
#: this share of that speed down by this factor ...
BELOW_DATA = (0.5, 1e-2)
#: ... and one above the fastest from this multiple of it up by this factor.
ABOVE_DATA = (2.0, 1e2)
#: A loosely determined parameter is taken over this many standard errors either side
#: of its value, and for a linear one not below this share of it.
LOOSE_SPREAD = 2.0
LOOSE_FLOOR = 0.1
#: A drop is seen when it is higher than this many noise floors.
SEEN_DROP = 3.0
#: Without a bound from the data, an open parameter spans its value times these.
AROUND_VALUE = {"V": (0.1, 10.0), "s": (0.1, 10.0), "Fc": (0.5, 1.5), "sigma": (0.1, 3.0),
                "n": (0.5, 2.0)}
#: Effects whose parameters the plan models (the others are held at their values).
MODELLED_EFFECTS = {"viscous": ("sigma",), "viscous-power": ("sigma", "n")}
#: SI units of the quantities a plan speaks of.
_SI = {"F": "N", "x": "m", "v": "m/s", "t": "s", "k": "N/s", "Fc": "N", "Fs": "N", "V": "m/s",
       "delta": "", "s": "1/m", "sigma": "N·s/m", "n": ""}


class PlanError(ValueError):
    """The request cannot be planned for; ``path`` locates the offending field (in the
    request: ``report``, ``params``, ``ranges``, ``limits``, …)."""

    def __init__(self, message: str, path: tuple = ()):
        super().__init__(message)
        self.path = tuple(path)


@dataclass
class Knowledge:
    """What a plan starts from.

    Attributes
    ----------
    values : dict of float
        Every planner parameter's current value (a placeholder where the data leave it
        open).
    determined : dict of bool
        Whether the data determine each parameter (all False without data).
    stderr : dict of float or None
        The data's standard errors.
    covariance : tuple or None
        ``(names, matrix)`` of the parameters with a standard error [their units], or
        None.
    given : dict of str
        Parameters taken as given rather than estimated, with why.
    ranges : dict of list
        The range each parameter the data do not determine is taken over, as pieces
        [(low, high), …] (two where it may lie on either side of the data), and
        ``why_open`` says where it comes from: two standard errors either side of a
        loosely determined value (one with a standard error, above the bar), or the
        bounds the data set on one they leave wholly open.
    noise : float or None
        The noise of one measured force of the record [N] (:func:`_record_noise`).
    """

    values: dict
    determined: dict
    stderr: dict
    covariance: tuple | None
    given: dict
    ranges: dict
    why_open: dict
    noise: float | None
    units: dict
    kind: str | None
    extent: dict
    F_hat: str = "avg"
    z_ba: float = 0.95
    mass: float | None = None
    notes: list = field(default_factory=list)

    @property
    def from_data(self) -> bool:
        return self.kind is not None


def _number(value, path, positive=False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise PlanError(f"{'.'.join(map(str, path))} must be a finite number, got {value!r}", path)
    if positive and value <= 0:
        raise PlanError(f"{'.'.join(map(str, path))} must be > 0, got {value!r}", path)
    return float(value)


def _units(given: dict) -> dict:
    rotary = given.get("x") in ("rad", "deg") or given.get("F") == "N·m"
    units = {key: unit_of(unit, rotary) for key, unit in _SI.items()}
    units.update({key: value for key, value in given.items()
                  if key in units and isinstance(value, str)})
    return units


def _drop_speeds(V: float, delta: float) -> tuple[float, float]:
    """Where the Stribeck term exp(−(v/V)^δ) has fallen to 0.9 and to 0.1 [m/s]."""
    return V * math.log(1 / 0.9) ** (1.0 / delta), V * math.log(10.0) ** (1.0 / delta)


def _seen_level(values, extent) -> float | None:
    """The fitted curve's friction at the slowest speed the data show it at: what the
    data set as a lower bound on Fs (None without an extent)."""
    shown = extent.get("speeds")
    if not shown:
        return None
    y = (shown[0] / values["V"]) ** values["delta"]
    return values["Fc"] + (values["Fs"] - values["Fc"]) * math.exp(-y)


def _open_speed_range(values, known, extent, noise, units) -> tuple[list, str]:
    """The pieces of the range an open V lies in, and why.

    A drop the data show (higher than the noise, falling within the speeds the data
    cover) with its shape open: V within those speeds. A drop the data do not show:
    the data see one level. When the data determine that level as Fc, the drop is over
    below the slowest speed; as Fs, it begins above the fastest; when they determine
    neither, it may lie on either side.
    """
    V, delta = values["V"], values["delta"]
    shown = extent.get("speeds")
    if not shown:
        low, high = AROUND_VALUE["V"]
        return [(V * low, V * high)], "the report gives no extent of the data"
    slowest, fastest = float(shown[0]), float(shown[1])
    begins, ends = _drop_speeds(V, delta)
    height = values["Fs"] - values["Fc"]
    if height > SEEN_DROP * (noise or 0.0) and ends > slowest and begins < fastest \
            and fastest > 3 * slowest:
        return [(slowest, fastest)], (f"the data show the drop between {slowest:.3g} and "
                                      f"{fastest:.3g} {units['v']} but not its shape")
    below = (BELOW_DATA[0] * slowest * BELOW_DATA[1], BELOW_DATA[0] * slowest)
    above = (ABOVE_DATA[0] * fastest, ABOVE_DATA[0] * fastest * ABOVE_DATA[1])
    flat = f"the data show one level from {slowest:.3g} to {fastest:.3g} {units['v']}"
    if known.get("Fc"):
        return [below], f"{flat}, and it is Fc: the drop is over below that, V lies below"
    if known.get("Fs"):
        return [above], f"{flat}, and it is Fs: the drop begins above that, V lies above"
    return [below, above], f"{flat}: the drop lies below or above it"


def _open_range(name, values, known, extent, noise, units) -> tuple[list, str]:
    """The pieces of the range an open parameter is taken over, and why."""
    if name == "V":
        return _open_speed_range(values, known, extent, noise, units)
    if name == "delta":
        return [DELTA_RANGE], "the shape of the drop is open"
    seen = _seen_level(values, extent)
    if name == "Fs":
        floor = max(values["Fc"] * 1.01, extent.get("held_force") or 0.0, seen or 0.0)
        return [(floor, floor + values["Fc"])], (
            f"the data set only Fs ≥ {floor:.4g} {units['F']}; taken up to Fc above that")
    if name == "Fc" and seen:
        return [(0.5 * seen, seen)], (f"the data set only Fc ≤ {seen:.4g} {units['F']}, the "
                                      "friction at the slowest speed they show")
    low, high = AROUND_VALUE.get(name, (0.5, 2.0))
    return [(values[name] * low, values[name] * high)], "taken around its fitted value"


def _loose_range(name, value, stderr, units) -> tuple[list, str]:
    """Two standard errors either side of a loosely determined value (a standard error,
    but above the bar for determined): on the log scale for the scales V and s, kept
    above zero for the others."""
    if name in LOG_PARAMETERS:
        spread = math.exp(LOOSE_SPREAD * stderr / value)
        piece = (value / spread, value * spread)
    else:
        piece = (max(value - LOOSE_SPREAD * stderr, LOOSE_FLOOR * value),
                 value + LOOSE_SPREAD * stderr)
    return [piece], (f"the data hold {symbol(name)} = {value:.3g} ± {stderr:.2g} "
                     f"{units.get(name, '')}, too loosely to call it determined").replace(" ,", ",")


def _user_ranges(ranges, path=("ranges",)) -> dict:
    out = {}
    for name, bounds in (ranges or {}).items():
        where = (*path, name)
        if name not in PARAMETERS:
            raise PlanError(f"unknown parameter {name!r} in ranges: expected one of "
                            f"{', '.join(PARAMETERS)}", where)
        if not isinstance(bounds, (list, tuple)) or len(bounds) != 2:
            raise PlanError(f"ranges.{name} must be [low, high]", where)
        low = _number(bounds[0], where, positive=name != "sigma")
        high = _number(bounds[1], where, positive=True)
        if not low < high:
            raise PlanError(f"ranges.{name} must have low < high, got [{low:g}, {high:g}]", where)
        out[name] = [(low, high)]
    return out


def _covariance(entry, errors: dict) -> tuple[list, list]:
    """``final.covariance`` of a report, over the parameters it gives a standard error."""
    where = ("report", "final", "covariance")
    names = entry.get("names") if isinstance(entry, dict) else None
    matrix = entry.get("matrix") if isinstance(entry, dict) else None
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names) \
            or not isinstance(matrix, list) or len(matrix) != len(names) \
            or not all(isinstance(row, list) and len(row) == len(names) for row in matrix):
        raise PlanError("report's final.covariance must hold names and a square matrix of "
                        "as many rows", where)
    keep = [i for i, n in enumerate(names) if errors.get(n) is not None]
    rows = [[matrix[i][j] for j in keep] for i in keep]
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
               for row in rows for v in row):
        raise PlanError("report's final.covariance.matrix must hold finite numbers", where)
    return [names[i] for i in keep], [[float(v) for v in row] for row in rows]


#: What a plan reads from a report's ``extent`` (numbers > 0), and its speed span.
_EXTENT_NUMBERS = ("force", "speed", "held_force", "travel", "duration", "sample_rate")


def _extent(given) -> dict:
    """The report's ``extent``, keeping only what is well formed (an older report has
    none; the plan then says it assumed what it lacks)."""
    if not isinstance(given, dict):
        return {}
    out = {key: _positive_or_none(given.get(key)) for key in _EXTENT_NUMBERS}
    span = given.get("speeds")
    if isinstance(span, list) and len(span) == 2:
        low, high = (_positive_or_none(v) for v in span)
        if low is not None and high is not None and low <= high:
            out["speeds"] = [low, high]
    return {key: value for key, value in out.items() if value is not None}


def _positive_or_none(value) -> float | None:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
    return float(value) if ok and value > 0 else None


def _record_noise(report: dict, fitted: int) -> float | None:
    """The noise of one measurement of the record: its scatter about the fit,
    ``rmse·√(n/(n − p))`` (what the fit's own standard errors are scaled by), where the
    residual is white; the larger of that and the model-free noise floor where it is not
    (structure the model lacks scatters a new record too)."""
    floor = _positive_or_none(report.get("noise_floor"))
    rmse = _positive_or_none((report.get("final") or {}).get("rmse"))
    n = report.get("n")
    scatter = None
    if rmse is not None and isinstance(n, int) and n > fitted:
        scatter = rmse * math.sqrt(n / (n - fitted))
    if scatter is None:
        return floor
    if report.get("residual_white") is True or floor is None:
        return scatter
    return max(floor, scatter)


def from_report(report, ranges=None) -> Knowledge:
    """What an identification report knows (see :class:`Knowledge`).

    Raises
    ------
    PlanError
        Naming the key of the report that is missing or wrong.
    """
    if not isinstance(report, dict):
        raise PlanError("a report must be a JSON object (the output of breakaway fit --json)",
                        ("report",))
    kind = report.get("kind")
    if kind not in ("timeseries", "steady", "breakaway"):
        raise PlanError("report.kind must be timeseries, steady or breakaway: not a "
                        "breakaway fit report", ("report", "kind"))
    final = report.get("final")
    if not isinstance(final, dict) or not isinstance(final.get("params"), dict):
        raise PlanError("report has no final.params", ("report", "final", "params"))
    params = final["params"]
    stderr = final.get("stderr") if isinstance(final.get("stderr"), dict) else {}
    determined = final.get("determined") if isinstance(final.get("determined"), dict) else {}
    effects = report.get("effects") or []
    if not isinstance(effects, list) or not all(isinstance(e, str) for e in effects):
        raise PlanError("report.effects must be a list of names", ("report", "effects"))
    units = _units(report.get("units") if isinstance(report.get("units"), dict) else {})
    extent = _extent(report.get("extent"))
    values, known, errors, given, notes = {}, {}, {}, {}, []
    for name in ("Fc", "Fs", "V", "delta"):
        if name not in params:
            raise PlanError(f"report's final.params lack {name}", ("report", "final", "params", name))
        values[name] = _number(params[name], ("report", "final", "params", name))
    modelled = {key for effect in effects for key in MODELLED_EFFECTS.get(effect, ())}
    for name in ("sigma", "n"):
        if name in modelled and name in params:
            values[name] = _number(params[name], ("report", "final", "params", name))
        else:
            values[name] = 0.0 if name == "sigma" else 1.0
            given[name] = "no viscous effect in the model" if name == "sigma" else \
                "the viscous term is linear"
    if kind == "timeseries":
        values["s"] = _number(params.get("s"), ("report", "final", "params", "s"), positive=True)
    elif kind == "breakaway":
        values["s"] = _number(report.get("s", 1.0), ("report", "s"), positive=True)
        given["s"] = (f"the presliding scale the break-away record was read with "
                      f"({values['s']:.4g} {units['s']})")
    else:
        values["s"] = math.nan  # a steady curve does not hold s: known only from ranges.s
    for name in values:
        if name in given:
            continue
        known[name] = bool(determined.get(name, False))
        se = stderr.get(name)
        finite = isinstance(se, (int, float)) and not isinstance(se, bool) and math.isfinite(se)
        errors[name] = float(se) if finite and se > 0 else None
    try:
        check_stribeck(values["Fc"], values["Fs"], values["V"], values["delta"], values["sigma"])
    except ValueError as err:
        raise PlanError(f"report's final.params: {err}", ("report", "final", "params",
                                                           str(err).split()[0])) from None
    user = _user_ranges(ranges)
    for name in user:  # a range given opens a parameter, whatever the data say of it
        given.pop(name, None)
        known[name], errors[name] = False, None
    if "s" in user and math.isnan(values["s"]):
        values["s"] = math.sqrt(user["s"][0][0] * user["s"][0][1])
    covariance = None
    entry = final.get("covariance")
    if entry is not None:
        covariance = _covariance(entry, errors)
    elif any(known.values()):
        names = [n for n in known if errors[n] is not None]
        covariance = (names, [[errors[a] ** 2 if a == b else 0.0 for b in names] for a in names])
        notes.append("The report gives no covariance: the parameters' correlations are "
                     "taken as zero, which understates what a plan can gain.")
    noise = _record_noise(report, len(params))
    open_ranges, why = {}, {}
    for name in known:
        if name in user:
            open_ranges[name], why[name] = user[name], "the range given"
        elif not known[name] and errors[name] is not None:
            open_ranges[name], why[name] = _loose_range(name, values[name], errors[name], units)
        elif not known[name] and not math.isnan(values[name]):
            open_ranges[name], why[name] = _open_range(name, values, known, extent, noise, units)
    other = [e for e in effects if e not in MODELLED_EFFECTS]
    if other:
        notes.append(f"The accepted effect{'s' if len(other) > 1 else ''} "
                     f"{', '.join(other)} {'are' if len(other) > 1 else 'is'} held at the "
                     "fitted values and not part of the plan's model.")
    return Knowledge(values, known, errors, covariance, given, open_ranges, why, noise, units,
                     kind, extent, notes=notes)


def from_params(params: dict, ranges=None, F_hat=None, z_ba=None) -> Knowledge:
    """What a set of model parameters (the explorer's) says: every value, nothing
    determined, no covariance; ``ranges`` open some parameters over a range instead."""
    values = {}
    for name in ("Fc", "Fs", "V", "delta", "s", "sigma"):
        raw = params.get(name, DEFAULTS[name])
        values[name] = _number(raw, ("params", name), positive=name not in ("delta", "sigma"))
    values["n"] = 1.0
    try:
        check_stribeck(values["Fc"], values["Fs"], values["V"], values["delta"], values["sigma"])
        F_hat = params.get("F_hat", DEFAULTS["F_hat"]) if F_hat is None else F_hat
        check_f_hat(F_hat)
        z_ba = float(params.get("z_ba", DEFAULTS["z_ba"]) if z_ba is None else z_ba)
        check_fraction("z_ba", z_ba)
    except ValueError as err:
        raise PlanError(str(err), ("params", str(err).split()[0])) from None
    given = {"n": "the viscous term is linear"}
    if values["sigma"] == 0:
        given["sigma"] = "no viscous friction in the model (σ = 0)"
    user = _user_ranges(ranges)
    for name in user:
        given.pop(name, None)
    known = {name: False for name in values if name not in given}
    mass = params.get("m")
    return Knowledge(values, known, {name: None for name in known}, None, given, user,
                     {name: "the range given" for name in user}, None, _units({}), None, {},
                     F_hat, z_ba, None if mass is None else _number(mass, ("params", "m"), True))


__all__ = ["DELTA_RANGE", "Knowledge", "PlanError", "from_params", "from_report"]
