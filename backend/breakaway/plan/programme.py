"""The programme a rig runs, as CSV: ``run,t,u`` for force ramps, ``run,v`` for
speed set-points, ``t,x`` for a position sine, with the units of the record in the
comment lines above the header."""

from __future__ import annotations

import numpy as np

#: Rows of one ramp in the programme (the ramp is linear; a rig that interpolates
#: needs only the first and the last).
RAMP_ROWS = 11
#: Rows per period of a sine programme at most (the rig's own sampling rate when that
#: is coarser): a smooth reference for a controller that interpolates between rows ...
SINE_ROWS_PER_PERIOD = 32
#: ... and rows of a sine programme at most (a long record of a fast sine is thinned
#: to this; the comment gives A and f to run it exactly).
SINE_MAX_ROWS = 100_000


def run_order(count: int) -> np.ndarray:
    """The order in which ``count`` runs are made: mixed, not sorted by their design
    variable, so that a slow drift of the rig (warming, wear) does not line up with the
    rate or the speed; seeded, so that the same plan gives the same programme."""
    return np.random.default_rng(0).permutation(count)


def _csv(comments: list[str], header: tuple[str, ...], table: np.ndarray) -> str:
    row = ",".join("{:d}" if name == "run" else "{:.8g}" for name in header).format
    columns = [table[:, j].astype(int).tolist() if name == "run" else table[:, j].tolist()
               for j, name in enumerate(header)]
    lines = [f"# {line}" for line in comments] + [",".join(header)]
    return "\n".join([*lines, *map(row, *columns)]) + "\n"


def ramps_csv(rates, ends, units: dict) -> str:
    """Force ramps ``u = k·t`` from rest, one per run, each up to its end force.

    Parameters
    ----------
    rates : array_like
        Rate of each run [N/s], in the order they are to be made.
    ends : array_like
        The force each ramp stops at [N] (never above the rig's largest force).
    units : dict
        Units of ``t`` and ``F`` (the record's: N·m for a rotary rig).
    """
    rates, ends = np.asarray(rates, dtype=float), np.asarray(ends, dtype=float)
    blocks = []
    for run, (k, u_end) in enumerate(zip(rates, ends), start=1):
        t = np.linspace(0.0, u_end / k, RAMP_ROWS)
        blocks.append(np.column_stack([np.full(t.size, run), t, k * t]))
    table = np.vstack(blocks) if blocks else np.empty((0, 3))
    comments = [
        "breakaway plan: force ramps u = k*t from rest, one per run; each stops at its "
        "last u (the rig's force limit, or the run's time) or when the body breaks away",
        f"units: run [-], t [{units['t']}], u [{units['F']}]",
        "rate of each run [" + units["k"] + "]: " + " ".join(f"{k:.6g}" for k in rates),
    ]
    return _csv(comments, ("run", "t", "u"), table)


def setpoints_csv(speeds, units: dict) -> str:
    """Constant-speed set-points, each run in both directions (two rows per run)."""
    speeds = np.asarray(speeds, dtype=float)
    runs = np.repeat(np.arange(1, speeds.size + 1), 2)
    table = np.column_stack([runs, np.ravel(np.column_stack([speeds, -speeds]))]) \
        if speeds.size else np.empty((0, 2))
    comments = [
        "breakaway plan: constant-speed set-points; each run holds +v, then -v, until "
        "the force has settled, and records the mean force",
        f"units: run [-], v [{units['v']}]",
    ]
    return _csv(comments, ("run", "v"), table)


def sine_csv(amplitude: float, frequency: float, duration: float, sample_rate: float,
             units: dict) -> str:
    """A position sine ``x = A·sin(2π·f·t)`` from rest at x = 0 for ``duration``
    seconds, at the rig's sampling rate or :data:`SINE_ROWS_PER_PERIOD` rows per
    period, whichever is coarser."""
    step = max(1.0 / sample_rate, 1.0 / (SINE_ROWS_PER_PERIOD * frequency),
               duration / SINE_MAX_ROWS)
    t = np.arange(0.0, duration + 0.5 * step, step) if amplitude > 0 else np.empty(0)
    table = np.column_stack([t, amplitude * np.sin(2 * np.pi * frequency * t)]) \
        if t.size else np.empty((0, 2))
    comments = [
        f"breakaway plan: position sine x = A*sin(2*pi*f*t), A = {amplitude:.6g} "
        f"{units['x']}, f = {frequency:.6g} Hz, from the virgin state (no motion "
        "before it); record t, x and the force; between rows the reference is the same "
        "sine",
        f"units: t [{units['t']}], x [{units['x']}]",
    ]
    return _csv(comments, ("t", "x"), table)


def empty_csv(header: tuple[str, ...], reason: str) -> str:
    """A programme with no runs, saying why."""
    return _csv([f"breakaway plan: nothing to run: {reason}"], header, np.empty((0, len(header))))


__all__ = ["RAMP_ROWS", "SINE_MAX_ROWS", "SINE_ROWS_PER_PERIOD", "empty_csv", "ramps_csv", "run_order", "setpoints_csv", "sine_csv"]
