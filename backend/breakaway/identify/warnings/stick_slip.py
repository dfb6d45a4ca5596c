"""``stick-slip``: the velocity itself sticks and slips, and a force
oscillation at that period is the stick-slip cycle, not position ripple."""

from __future__ import annotations

from . import warning


def stick_slip_warnings(problem) -> list[dict]:
    """One ``stick-slip`` warning when the record sticks and slips."""
    cycle = getattr(problem, "stick_slip", None)
    if cycle is None:
        return []
    unit, length = problem.data.unit("N"), problem.data.unit("m")
    return [warning("stick-slip", None, (
        f"the body sticks and slips: {cycle.cycles} stick phases, a slip every "
        f"{cycle.period:.3g} s over {cycle.travel:.3g} {length}, at rest "
        f"{100 * cycle.rest_share:.0f} % of the time while the load builds up by "
        f"{cycle.load_rise:.3g} {unit} in each stick; the force oscillates with that cycle "
        f"(friction falling with speed against the drive's stiffness), so ripple is not "
        f"accepted at that wavelength"))]


__all__ = ["stick_slip_warnings"]
