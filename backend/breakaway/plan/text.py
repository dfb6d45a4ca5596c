"""A plan as the text ``breakaway plan`` prints: the design, the standard errors
predicted before and after, and the notes."""

from __future__ import annotations

from .curve import symbol


def _number(value, unit: str = "") -> str:
    if value is None:
        return "—"
    return f"{value:.3g} {unit}".rstrip()


def _listed(values) -> str:
    """Values in order, a repeated one once with its count: ``0.1 (×3), 2``."""
    counted = {}
    for value in values:
        counted[value] = counted.get(value, 0) + 1
    return ", ".join(f"{v:.3g}" + (f" (×{n})" if n > 1 else "") for v, n in counted.items())


def _design_lines(design: dict, units: dict) -> list[str]:
    family = design["family"]
    if family == "ramps":
        rates = design["rates"]
        return [f"  {len(rates)} force ramps from rest at k [{units['k']}]: {_listed(rates)}",
                f"  break-away speeds {min(design['breakaway_speed']):.3g} to "
                f"{max(design['breakaway_speed']):.3g} {units['v']}; each ramp stops at "
                f"{max(design['end_force']):.4g} {units['F']} at most"]
    if family == "steady":
        speeds = design["speeds"]
        return [f"  {len(speeds)} set-points, each at +v and -v, v [{units['v']}]: "
                f"{_listed(speeds)}"]
    return [f"  one position sine: A = {design['amplitude']:.3g} {units['x']}, "
            f"f = {design['frequency']:.3g} Hz, {design['duration']:.3g} s "
            f"({design['periods']:.3g} periods) at {design['sample_rate']:.3g} Hz; peak speed "
            f"{design['peak_speed']:.3g} {units['v']}, peak force {design['peak_force']:.3g} "
            f"{units['F']}"]


def format_plan(plan: dict, programme_path: str | None = None) -> str:
    """The plan as text for a terminal."""
    units = plan["units"]
    targets = ", ".join(symbol(t) for t in plan["targets"]) or "nothing"
    lines = [f"breakaway plan: {plan['family']}, to determine {targets}", ""]
    design = plan["design"]
    if design:
        lines.append("design:")
        lines += _design_lines(design, units)
    else:
        lines.append("design: no runs")
    lines += ["", "predicted standard errors:",
              f"  {'':8}{'now':>18}{'after':>18}   determined"]
    for name, entry in plan["predicted"].items():
        unit = units.get(name, "")
        yes = {True: "yes", False: "no"}
        lines.append(f"  {symbol(name):8}{_number(entry['stderr_now'], unit):>18}"
                     f"{_number(entry['stderr_after'], unit):>18}   "
                     f"{yes[entry['determined_now']]} -> {yes[entry['determined_after']]}"
                     + ("  (target)" if entry["target"] else ""))
        for point in entry.get("across") or []:
            lines.append(f"  {'':8}{'at ' + _number(point['value'], unit):>18}"
                         f"{_number(point['stderr_after'], unit):>18}   "
                         f"{yes[point['determined_after']]}")
    if plan["notes"]:
        lines += ["", "notes:"] + [f"  - {note}" for note in plan["notes"]]
    if design:
        where = f"written to {programme_path}" if programme_path else "give -o FILE to write it"
        lines += ["", f"programme ({plan['family']}): {where}"]
    return "\n".join(lines) + "\n"


__all__ = ["format_plan"]
