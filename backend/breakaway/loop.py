"""The position loop as the loop view and ``POST /api/loop`` show it:
the run's time series, its stick phases beside the note's (E13), hunting and the RMS
error.

While the body sticks with e ≠ 0 the integral term ramps u at ``k = Ki·|e|``, so each stick
ends in a break-away like the ramp experiment's, which (E13) predicts at that k. A
stick phase runs from a change of sign of ẋ (the first after a break-away), or t = 0,
to the next break-away: the presliding fraction reaching z* on the current branch
(:mod:`breakaway.dynamics.loop_model`). With the presliding model the body never
sits still while it sticks: it creeps, and chatters through reversals, inside the
presliding distance; those reversals start new branches but not new phases.
"""

from __future__ import annotations

import math

import numpy as np

from .dynamics import simulate_loop
from .dynamics.common import EVENT_BREAKAWAY, EVENT_STICK
from .dynamics.loop_model import plant_steady
from .params import LUGRE_1995, check_f_hat
from .quasistatic import breakaway_force


def stick_phases(t, u, v, F, code):
    """The stick phases of a loop run: start, break-away, rate and force.

    Parameters
    ----------
    t, u, v, F : array_like
        Time [s], control force [N], velocity [m/s] and friction [N] of each sample.
    code : array_like of int
        Event code of each sample (:mod:`breakaway.dynamics.common`); the first sample
        (t = 0) starts a phase.

    Returns
    -------
    dict of numpy.ndarray
        Per completed phase: ``t_start``, ``t_ba`` [s], ``u_start``, ``u_ba`` [N] (u at
        break-away), ``F_ba`` [N] (friction there), ``direction`` (±1, the sign of ẋ at
        break-away) and ``k`` [N/s]: the mean rate of u over the phase towards the
        break-away, ``direction·(u_ba − u_start)/(t_ba − t_start)``.
    """
    t, u, v, F = (np.asanyarray(a, dtype=float) for a in (t, u, v, F))
    code = np.asanyarray(code)
    start, begin, end = 0, [], []
    for i in np.flatnonzero(code & (EVENT_BREAKAWAY | EVENT_STICK)):
        if code[i] & EVENT_BREAKAWAY and start is not None:
            begin.append(start)
            end.append(i)
            start = None
        if code[i] & EVENT_STICK:
            start = i
    begin, end = np.array(begin, dtype=int), np.array(end, dtype=int)
    direction = np.where(v[end] < 0, -1.0, 1.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        k = direction * (u[end] - u[begin]) / (t[end] - t[begin])
    return {"t_start": t[begin], "t_ba": t[end], "u_start": u[begin], "u_ba": u[end],
            "F_ba": F[end], "direction": direction, "k": k}


def phase_e13(k, direction, steady, s, F_hat, z_ba):
    """(E13) at each phase's rate, signed like its break-away; NaN where k <= 0 (u did
    not ramp towards the break-away: E13 has nothing to say).

    ``steady``: Fc, Fs, V, delta, sigma of (E2); ``s`` [1/m]; ``F_hat``; ``z_ba``.
    """
    k = np.asanyarray(k, dtype=float)
    out = np.full(k.shape, np.nan)
    ramped = np.isfinite(k) & (k > 0)
    if np.any(ramped):
        out[ramped] = direction[ramped] * breakaway_force(
            k[ramped], steady["Fc"], steady["Fs"], steady["V"], steady["delta"], s,
            steady["sigma"], F_hat, z_ba)
    return out


def hunting(t_ba, direction, t, e, t_end):
    """The stick-slip limit cycle, or None when the loop settles.

    Hunting: the last half of the run, ``t >= t_end/2``, holds at least two break-aways.
    ``period`` is their mean spacing [s], ``amplitude`` half the peak-to-peak of e there
    [m]; besides, ``count`` (break-aways there) and ``cycle`` [s], the mean spacing of
    break-aways in the same direction (one full cycle when they alternate: twice
    ``period``), None when no direction breaks away twice.

    Parameters
    ----------
    t_ba, direction : array_like
        Break-away times [s] and directions (±1).
    t, e : array_like
        The error e [m] on the uniform output grid t [s].
    t_end : float
        Where the run ended [s].
    """
    t_ba, direction = np.asanyarray(t_ba, dtype=float), np.asanyarray(direction, dtype=float)
    late = t_ba >= 0.5 * t_end
    if np.count_nonzero(late) < 2:
        return None
    times, sides = t_ba[late], direction[late]
    e = np.asanyarray(e, dtype=float)[np.asanyarray(t) >= 0.5 * t_end]
    spacings = [np.diff(times[sides == side]) for side in (-1.0, 1.0)]
    same = np.concatenate(spacings)
    return {"period": float(np.mean(np.diff(times))),
            "amplitude": float(0.5 * np.ptp(e)) if e.size else math.nan,
            "count": int(times.size),
            "cycle": float(np.mean(same)) if same.size else None}


def rms_error(t, e):
    """RMS of e over the run, ``sqrt(∫e² dt / T)`` [m] (trapezoids on the grid t)."""
    t, e = np.asanyarray(t, dtype=float), np.asanyarray(e, dtype=float)
    if t.size < 2 or t[-1] <= t[0]:
        return math.nan
    return float(np.sqrt(np.trapezoid(e * e, t) / (t[-1] - t[0])))


def loop_experiment(model: str, params: dict, controller: dict, reference: dict,
                    duration: float, compensation: dict | None = None, F_hat: str = "avg",
                    points: int = 2000, max_steps: int = 2_000_000) -> dict:
    """One run of the position loop with everything the loop view shows.

    Parameters are those of :func:`breakaway.dynamics.simulate_loop`; ``F_hat`` is the
    level of the phases' (E13) values. For LuGre these use its steady state (vs as V,
    σ2 as σ) and s = σ0/Fs, the bristle deflection at stiction as presliding distance.

    Returns
    -------
    dict
        ``t, r, x, v, u, F, e`` (numpy arrays: the uniform grid of ``points`` samples
        with each break-away and stick-phase start inserted at its time),
        ``stick_phases`` (list of dicts: ``t_start, t_ba, k, u_ba, E13`` and
        ``u_start, F_ba, direction``; E13 None where k <= 0), ``hunting`` (dict or
        None, see :func:`hunting`), ``rms_error`` [m] (on the grid), ``t_end``,
        ``runaway``, ``reversals``.
    """
    check_f_hat(F_hat)
    run = simulate_loop(params, controller, reference, duration, compensation, model, points,
                        max_steps=max_steps)
    phases = stick_phases(run.t, run.u, run.v, run.F, run.code)
    if model == "lugre":
        plant = {**LUGRE_1995, **params}
        s = plant["sigma0"] / plant["Fs"]
    else:
        plant, s = params, params["s"]
    e13 = phase_e13(phases["k"], phases["direction"], plant_steady(model, plant), s, F_hat,
                    params["z_ba"])
    grid = run.code == 0
    hunt = None if run.runaway else hunting(phases["t_ba"], phases["direction"], run.t[grid],
                                            run.e[grid], run.t_end)
    rows = [dict(zip(phases, values)) for values in zip(*phases.values())]
    for row, value in zip(rows, e13):
        row["E13"] = _finite_or_none(value)
        row["direction"] = int(row["direction"])
        for key in ("t_start", "t_ba", "k", "u_ba", "u_start", "F_ba"):
            row[key] = _finite_or_none(row[key])
    return {"t": run.t, "r": run.r, "x": run.x, "v": run.v, "u": run.u,
            "F": run.F, "e": run.e, "stick_phases": rows, "hunting": hunt,
            "rms_error": _finite_or_none(rms_error(run.t[grid], run.e[grid])),
            "t_end": float(run.t_end), "runaway": bool(run.runaway),
            "reversals": int(run.reversals)}


def _finite_or_none(value):
    value = float(value)
    return value if math.isfinite(value) else None


__all__ = ["hunting", "loop_experiment", "phase_e13", "rms_error", "stick_phases"]
