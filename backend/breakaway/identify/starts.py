"""Starting points of a fit, read off the data: levels from the sliding plateaus and
peaks, a grid of Stribeck velocities, shapes and presliding distances for the base
model, and each effect's values read off the current residual
(:meth:`~.effects.base.Effect.starts`)."""

from __future__ import annotations

import numpy as np

from .effects import EFFECTS
from .models import Problem


def _level_guesses(problem: Problem):
    """Coulomb and Stribeck levels from the data (sliding plateaus and peaks)."""
    kind = problem.data.kind
    F = problem.measured
    if kind == "breakaway":
        lo, hi = np.percentile(F, [5, 95])
        return max(float(lo), 1e-6 * problem.scales.force), max(float(hi), float(lo))
    speed = np.abs(problem.v)
    fast = speed >= np.percentile(speed, 70)
    if kind == "timeseries":
        along = np.sign(F) == problem.d
        fast &= along
    Fc = float(np.median(np.abs(F[fast]))) if np.any(fast) else problem.scales.force
    Fs = float(np.percentile(np.abs(F), 98))
    Fc = max(Fc, 1e-6 * problem.scales.force)
    return Fc, max(Fs, Fc)


#: Stribeck velocities of the starts, as shares of the record's typical speed (the 95th
#: percentile of |v|) ...
TYPICAL_SHARES = (0.03, 0.1, 0.3, 1.0)
#: ... and of its fastest, where that is further out: a record that moves in short slips
#: between long creeps has its typical speed among the creeps.
FASTEST_SHARES = (0.03, 0.1, 0.3)
#: Two starts' Stribeck velocities within this factor are one.
SPEED_FACTOR = 2.0


def _stribeck_speeds(problem: Problem) -> list[float]:
    """The starts' Stribeck velocities [m/s] (:data:`TYPICAL_SHARES`,
    :data:`FASTEST_SHARES`): on a stick-slip record whose slips are a twentieth of its
    rows, the typical speed is a creep's, and a grid below it alone missed the drop
    where the slips start."""
    typical = problem.scales.speed
    speeds = [typical * share for share in TYPICAL_SHARES]
    v = getattr(problem, "v", None)
    fastest = float(np.max(np.abs(v))) if v is not None and np.size(v) else typical
    for speed in (fastest * share for share in FASTEST_SHARES):
        if all(max(speed / kept, kept / speed) >= SPEED_FACTOR for kept in speeds):
            speeds.append(speed)
    return speeds


def base_starts(problem: Problem) -> list[dict]:
    """A grid of starting points for the base parameters (levels from the data)."""
    Fc, Fs = _level_guesses(problem)
    if problem.level_only:
        return [{"Fc": float(np.median(problem.measured)), "Fs": float(np.median(problem.measured)),
                 **problem.fixed}]
    starts = []
    for V in _stribeck_speeds(problem):
        for delta in (1.0, 2.0):
            p = {"Fc": Fc, "Fs": max(Fs, 1.02 * Fc), "V": float(V), "delta": delta}
            if problem.data.kind == "timeseries":
                for zs in (0.003, 0.01, 0.03, 0.1, 0.3, 1.0):
                    # presliding distance 1/s as a fraction of the travel
                    starts.append({**p, "s": 1.0 / (zs * problem.scales.travel)})
            else:
                starts.append(p)
    return starts


def effect_starts(problem: Problem, effect: str, current: dict, residual: np.ndarray) -> list[dict]:
    """Starting values of one effect's parameters from the current residual."""
    return EFFECTS[effect].starts(problem, current, residual)


__all__ = ["base_starts", "effect_starts"]
