"""What no run of a family can determine within the rig's limits, and why: the plan
says so, with the numbers, rather than propose runs that cannot help.

- Break-away forces depend on V and s only through s·V (E12 holds k/s, E2 holds
  ẋ/V): ramps alone cannot separate the two.
- The steady curve does not depend on s, and a rig holds no speed below the slowest it
  keeps steady: a Stribeck drop below that speed needs presliding data (break-away at
  slow rates, or a sine through reversals).
- A ramp yields nothing where it would break away above the force limit or after the
  run's time.
"""

from __future__ import annotations

import math

import numpy as np

from .curve import symbol

#: Which families can show what a family cannot.
OTHER_FAMILIES = {"ramps": ("sine", "steady"), "steady": ("ramps", "sine"),
                  "sine": ("ramps", "steady")}


def not_measured(name: str, family: str) -> str:
    """Why ``family``'s measurement says nothing about ``name``, and what would."""
    if name == "s":
        return ("the steady curve does not depend on the presliding scale s: a sine "
                "through presliding and reversals determines it")
    if name == "n":
        return ("a break-away force is read with a linear viscous term: set-points at "
                "speeds where the viscous part shows determine the exponent n")
    return f"the {family} measurement does not depend on {symbol(name)}"


def _fmt(value: float) -> str:
    return f"{value:.3g}"


def why_open(outcome, knowledge, name: str) -> list[str]:
    """Sentences on why the plan leaves the target ``name`` open at some draws."""
    family, names = outcome.family.name, outcome.names
    units, limits = knowledge.units, outcome.setting.limits
    out = []
    pair = {"V": "s", "s": "V"}.get(name)
    if family == "ramps" and pair in names and not knowledge.determined.get(pair, False):
        out.append(f"break-away forces depend on V and s only through s·V (the break-away "
                   f"speed is k/(s·F̂·|ln z*|), the curve falls with speed/V): ramps alone "
                   f"cannot separate {symbol(name)} from {symbol(pair)}; a sine through presliding and "
                   f"reversals determines s, and with it V")
    draws = outcome.draws
    column = names.index(name)
    # the draws the answer reports on: the target across its range, the others at their
    # middle (or the middle draw alone)
    reported = np.asarray(draws.across.get(name) or [draws.middle])
    failing = reported[~outcome.determined_after[reported, column]]
    if family == "steady" and name in ("V", "delta", "Fs") and failing.size:
        P = draws.P
        # where half of the drop is done: exp(−(v/V)^δ) = 1/2
        half = P["V"][failing, 0] * np.power(math.log(2.0), 1.0 / P["delta"][failing, 0])
        below = half < limits.v_min
        if below.any():
            worst = failing[below][0]
            out.append(f"at V = {_fmt(P['V'][worst, 0])} {units['V']} half of the Stribeck drop "
                       f"is done by {_fmt(half[below][0])} {units['v']}, below the slowest speed "
                       f"the rig holds (v_min = {_fmt(limits.v_min)} {units['v']}): set-points "
                       "cannot show it; it needs presliding data (ramps at slow rates, whose "
                       "break-away speed goes far lower, or a sine through reversals)")
    if name in ("V", "delta") and failing.size:
        P = draws.P
        # where the drop begins: exp(−(v/V)^δ) = 0.9
        begins = P["V"][failing, 0] * np.power(math.log(1 / 0.9), 1.0 / P["delta"][failing, 0])
        above = begins > limits.v_max
        if above.any():
            worst = failing[above][0]
            out.append(f"at V = {_fmt(P['V'][worst, 0])} {units['V']} the Stribeck drop begins "
                       f"at {_fmt(begins[above][0])} {units['v']}, above the largest speed the "
                       f"rig may reach (v_max = {_fmt(limits.v_max)} {units['v']}): only a "
                       "faster rig shows it")
    if family == "ramps" and name in ("V", "delta") and failing.size \
            and outcome.information is not None:
        P = draws.P
        begins = P["V"][failing, 0] * np.power(math.log(1 / 0.9), 1.0 / P["delta"][failing, 0])
        # the slowest break-away speed a ramp reaches: the slowest rate that breaks away
        # within its run (per draw)
        speeds = np.where(outcome.information.usable, outcome.information.predicted["speed"],
                          np.inf)[failing].min(axis=1)
        early = begins < speeds
        if early.any():
            worst = failing[early][0]
            out.append(f"at V = {_fmt(P['V'][worst, 0])} {units['V']} the Stribeck drop begins "
                       f"at {_fmt(begins[early][0])} {units['v']}, below the slowest break-away "
                       f"speed a ramp reaches within {_fmt(limits.duration)} s "
                       f"({_fmt(speeds[early][0])} {units['v']}): slower ramps, in longer runs, "
                       "would show it")
    if outcome.information is not None and failing.size:
        silent = ~outcome.information.usable[failing].any(axis=1)
        if silent.any():
            q = failing[silent][0]
            at = ", ".join(f"{n} = {_fmt(draws.P[n][q, 0])}" for n in draws.levels)
            out.append(f"at {at} no {family} run within the limits yields a measurement "
                       f"(u_max = {_fmt(limits.u_max)} {units['F']}, "
                       f"{_fmt(limits.duration)} s per run)")
    return out


def open_values(outcome, name: str) -> str | None:
    """Where over its open range the plan leaves ``name`` undetermined, in words, or
    None when it is determined everywhere (or is not open)."""
    draws = outcome.draws
    if name not in draws.levels:
        return None
    column = outcome.names.index(name)
    levels = draws.levels[name]
    ok = outcome.determined_after[draws.across[name], column]
    if ok.all():
        return None
    if not ok.any():
        return "anywhere in its range"
    return "at " + ", ".join(_fmt(v) for v, good in zip(levels, ok) if not good)


__all__ = ["OTHER_FAMILIES", "not_measured", "open_values", "why_open"]
