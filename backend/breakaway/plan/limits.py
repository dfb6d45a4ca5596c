"""The rig's limits of a plan: those given, and for the others what the record shows
the rig did (its largest force and speed, its travel, length and sampling rate) or,
without a record, a stated assumption."""

from __future__ import annotations

import math

from .knowledge import Knowledge, PlanError
from .setting import Limits

#: Without a record: the force limit as a multiple of the Stribeck level, the speed
#: limit and the slowest held speed as multiples of V.
FORCE_OVER_LEVEL = 2.0
SPEED_OVER_V = 10.0
SLOWEST_OVER_V = 0.01
#: The slowest speed a rig holds, as a share of its largest, where the record does not
#: show one (it was not a steady curve).
SLOWEST_SHARE = 1e-3
#: A run's length and the sampling rate where the record does not show them.
DEFAULT_DURATION = 60.0
DEFAULT_SAMPLE_RATE = 1000.0
NAMES = ("u_max", "v_max", "v_min", "travel", "duration", "sample_rate")


def _positive(name, value):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or value <= 0:
        raise PlanError(f"limits.{name} must be a finite number > 0, got {value!r}",
                        ("limits", name))
    return float(value)


def _defaults(knowledge: Knowledge) -> dict[str, tuple[float | None, str]]:
    """Each limit's default and where it comes from."""
    values, extent = knowledge.values, knowledge.extent
    level = max(values["Fs"], values["Fc"])
    if knowledge.from_data:
        shown = extent.get("speeds")
        out = {"u_max": (extent.get("force"), "the largest force the record reached"),
               "v_max": (extent.get("speed"), "the largest speed the record reached"),
               "v_min": ((shown[0], "the slowest speed of the record")
                         if knowledge.kind == "steady" and shown else (None, "")),
               "travel": (extent.get("travel"), "the record's travel"),
               "duration": (extent.get("duration"), "the record's length"),
               "sample_rate": (extent.get("sample_rate"), "the record's sampling rate")}
    else:
        out = {"u_max": (FORCE_OVER_LEVEL * level, f"{FORCE_OVER_LEVEL:g}·Fs"),
               "v_max": (SPEED_OVER_V * values["V"], f"{SPEED_OVER_V:g}·V"),
               "v_min": (SLOWEST_OVER_V * values["V"], f"{SLOWEST_OVER_V:g}·V")}
    out.setdefault("travel", (None, ""))
    if out["u_max"][0] is None:
        out["u_max"] = (FORCE_OVER_LEVEL * level, f"{FORCE_OVER_LEVEL:g}·Fs")
    if out["v_max"][0] is None:
        out["v_max"] = (SPEED_OVER_V * values["V"], f"{SPEED_OVER_V:g}·V")
    if out.get("duration", (None,))[0] is None:
        out["duration"] = (DEFAULT_DURATION, f"{DEFAULT_DURATION:g} s per run")
    if out.get("sample_rate", (None,))[0] is None:
        out["sample_rate"] = (DEFAULT_SAMPLE_RATE, f"{DEFAULT_SAMPLE_RATE:g} samples per second")
    return out


def _unit(name: str, units: dict) -> str:
    return {"u_max": units["F"], "v_max": units["v"], "v_min": units["v"], "travel": units["x"],
            "duration": units["t"], "sample_rate": "Hz"}[name]


def resolve_limits(knowledge: Knowledge, given: dict | None, uses=NAMES
                   ) -> tuple[Limits, list[str]]:
    """The limits of the plan, and a sentence on where those not given came from.

    Parameters
    ----------
    knowledge : Knowledge
    given : dict, optional
        Limits given (keys of :data:`NAMES`; a missing or None one takes its default).
    uses : sequence of str
        The limits the family's runs are bound by (the sentence names only these).
    """
    given = {k: v for k, v in (given or {}).items() if v is not None}
    unknown = set(given) - set(NAMES)
    if unknown:
        name = sorted(unknown)[0]
        raise PlanError(f"unknown limit {name!r}: expected {', '.join(NAMES)}", ("limits", name))
    given = {name: _positive(name, value) for name, value in given.items()}
    defaults = _defaults(knowledge)
    limits, source = {}, []
    for name in NAMES:
        if name in given:
            limits[name] = given[name]
            continue
        limits[name], why = defaults.get(name, (None, ""))
        if name in uses and limits[name] is not None:
            source.append(f"{name} = {limits[name]:.4g} {_unit(name, knowledge.units)} ({why})")
    if limits["v_min"] is None:
        limits["v_min"] = SLOWEST_SHARE * limits["v_max"]
        if "v_min" in uses:
            source.append(f"v_min = {limits['v_min']:.4g} {knowledge.units['v']} "
                          f"({SLOWEST_SHARE:g}·v_max)")
    if not limits["v_min"] < limits["v_max"]:
        raise PlanError(f"limits.v_min must be below v_max = {limits['v_max']:.4g} "
                        f"{knowledge.units['v']}, got {limits['v_min']:.4g}", ("limits", "v_min"))
    notes = [f"Limits not given: {'; '.join(source)}."] if source else []
    return Limits(**limits), notes


__all__ = ["DEFAULT_DURATION", "DEFAULT_SAMPLE_RATE", "NAMES", "resolve_limits"]
