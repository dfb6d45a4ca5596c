"""A plan's numbers as its answer: the design, the standard errors predicted before
and after per parameter (and across an open range), the programme and the notes that
say what was assumed and what the family cannot do."""

from __future__ import annotations

import math

import numpy as np

from .curve import PARAMETERS, SYMBOLS, symbol
from .honesty import OTHER_FAMILIES, open_values, why_open
from .sensitivity import rate_band


def _clean(value):
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def json_safe(value):
    """``value`` with every non-finite number (and NumPy scalar) made JSON-safe: NaN
    and infinities become None."""
    if isinstance(value, dict):
        return {key: json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_safe(item) for item in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return _clean(value)
    return value


def _predicted(outcome, knowledge) -> dict:
    """Per parameter of the plan's model and per target it drops: ``stderr_now``,
    ``stderr_after``, ``determined_now``, ``determined_after``, ``target``, and for an
    open one ``range`` and ``across`` (the values across it)."""
    out = {}
    draws = outcome.draws
    planned = outcome.stderr_after is not None
    for column, name in enumerate(outcome.names):
        now = knowledge.stderr.get(name)
        entry = {"stderr_now": _clean(now),
                 "determined_now": bool(knowledge.determined.get(name, False)),
                 "target": name in outcome.targets}
        if planned:
            entry["stderr_after"] = _clean(outcome.stderr_after[draws.middle, column])
            entry["determined_after"] = outcome.determined_over_range(name)
        else:
            entry["stderr_after"] = entry["stderr_now"]
            entry["determined_after"] = entry["determined_now"]
        if name in knowledge.ranges:
            pieces = knowledge.ranges[name]
            entry["range"] = [float(pieces[0][0]), float(pieces[-1][1])]
            if len(pieces) > 1:
                entry["pieces"] = [[float(a), float(b)] for a, b in pieces]
            entry["why_open"] = knowledge.why_open.get(name)
            if planned and name in draws.across:
                entry["across"] = [
                    {"value": float(value), "stderr_after": _clean(outcome.stderr_after[q, column]),
                     "determined_after": bool(outcome.determined_after[q, column])}
                    for value, q in zip(draws.levels[name], draws.across[name])]
        out[name] = entry
    for name in outcome.dropped:
        if name in out or name not in knowledge.stderr:
            continue
        se = _clean(knowledge.stderr.get(name))
        determined = bool(knowledge.determined.get(name, False))
        out[name] = {"stderr_now": se, "stderr_after": se, "determined_now": determined,
                     "determined_after": determined, "target": False}
    return out


def _sentence(text: str) -> str:
    """``text`` as a sentence: a capital first letter, unless it starts with a
    parameter's symbol (s, δ), which keeps its case."""
    first = text.split(" ", 1)[0]
    if first in PARAMETERS or first in SYMBOLS.values():
        return text + "."
    return text[0].upper() + text[1:] + "."


def _open_sentence(knowledge, outcome) -> list[str]:
    units = knowledge.units
    out = []
    for name in outcome.names:
        if name in knowledge.ranges:
            unit = units.get(name, "")
            spans = " and ".join(f"from {low:.3g} to {high:.3g}"
                                 for low, high in knowledge.ranges[name])
            out.append(f"{symbol(name)} is not determined: {knowledge.why_open.get(name)}; the plan "
                       f"holds for {symbol(name)} {spans} {unit}".rstrip() + ".")
    return out


def describe(outcome, knowledge, would) -> dict:
    """The answer of :func:`~.planner.plan_experiment`; ``would(family, names)`` says
    which of ``names`` a plan of another family determines."""
    family, setting = outcome.family, outcome.setting
    notes = list(knowledge.notes) + list(outcome.notes)
    notes += _open_sentence(knowledge, outcome)
    notes += [_sentence(text) for text in outcome.dropped.values()]
    design = None
    reason = ""
    if not outcome.targets:
        reason = "every parameter asked for is determined or not measured by this family"
        notes.append("Nothing new to measure: the plan proposes no runs.")
    elif outcome.candidates is None or outcome.candidates.size == 0:
        reason = outcome.candidates.why_none if outcome.candidates else "no candidate run"
        notes.append(f"No {family.name} run fits within the limits: {reason}.")
    else:
        design = {"family": family.name, "runs": int(np.sum(outcome.counts)),
                  **family.design(outcome.counts, outcome.candidates, outcome.information,
                                  outcome.draws.middle, setting),
                  "draws": outcome.draws.count,
                  "criterion": {"before": outcome.before, "after": outcome.after}}
        if family.name == "ramps":
            design["band"] = _band(outcome, knowledge)
        if not np.any(outcome.information.usable):
            notes.append(f"No {family.name} run within the limits yields a measurement at "
                         "any of the values the plan is made for.")
        notes += _left_open(outcome, knowledge, would)
    return {
        "family": family.name,
        "targets": list(outcome.targets),
        "design": design,
        "predicted": _predicted(outcome, knowledge),
        "programme": family.programme(design, setting, reason),
        "notes": notes,
        "limits": setting.limits.as_dict(),
        "noise": setting.noise,
        "units": {key: knowledge.units[key] for key in sorted(knowledge.units)},
    }


def _band(outcome, knowledge) -> dict | None:
    """Where F_ba(k) is most sensitive to V and δ at the middle draw (a teaching figure of
    the plan: the rates it chooses cluster there)."""
    p = outcome.draws.at(outcome.draws.middle)
    return rate_band(p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"],
                     knowledge.F_hat, knowledge.z_ba)


def _left_open(outcome, knowledge, would) -> list[str]:
    """Notes on each target the plan leaves open somewhere, and the family that would
    determine it."""
    notes = []
    for name in outcome.targets:
        if outcome.determined_over_range(name):
            continue
        where = open_values(outcome, name)
        unit = knowledge.units.get(name, "")
        place = f" {where}" if where else ""
        reasons = why_open(outcome, knowledge, name)
        text = (f"Within these limits no {outcome.family.name} plan determines {symbol(name)}"
                f"{place}{(' ' + unit) if where and where != 'anywhere in its range' and unit else ''}")
        if reasons:
            text += ": " + "; ".join(reasons)
        others = [other for other in OTHER_FAMILIES[outcome.family.name]
                  if name in would(other, [name])]
        if others:
            text += f". A {' or a '.join(others)} plan would determine it"
        notes.append(text + ".")
    return notes


__all__ = ["describe", "json_safe"]
