"""The Python side of the integrator: the runs' results, the models' entries in the
table, tolerance checks, and the calls into the compiled :mod:`.integrator` (a sweep
over rates, one recorded ramp, one run on an output grid)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..params import check_positive
from .integrator import STATUS_BREAKAWAY, _integrate, _sweep
from .lugre import _L_K
from .ramp_model import _P_K
from .table import MODEL_LOOP_LUGRE, MODEL_LOOP_PRESLIDING, MODEL_LUGRE, MODEL_PRESLIDING


@dataclass(frozen=True)
class RampBreakaway:
    """Break-away of a ramp experiment for each rate.

    Attributes
    ----------
    k : numpy.ndarray
        Actuation force rates [N/s].
    u_ba : numpy.ndarray
        Actuation force at break-away ``k·t_ba`` [N] (what an experiment reports).
    F_ba : numpy.ndarray
        Friction at break-away [N].
    t_ba : numpy.ndarray
        Break-away time [s]; NaN where no break-away happened before the time limit.
    reversals : numpy.ndarray
        Number of motion reversals before break-away.
    """

    k: np.ndarray
    u_ba: np.ndarray
    F_ba: np.ndarray
    t_ba: np.ndarray
    reversals: np.ndarray


@dataclass(frozen=True)
class Trajectory:
    """One simulated ramp: samples at the accepted steps and events."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    F: np.ndarray
    u: np.ndarray
    t_ba: float
    F_ba: float
    reversals: int
    #: LuGre's bristle deflection z [m] per sample (None for the presliding model)
    bristle: np.ndarray | None = None


#: Default relative tolerance of the adaptive integrator. On the default preset the
#: 15-rate Fig. 3 sweep then agrees with rtol = 1e-12 to 0.3 % (see benchmarks/).
DEFAULT_RTOL = 1e-6
#: Tightest tolerance accepted; below it the step size underflows on long chattering runs.
MIN_RTOL = 1e-12
#: Largest step as a fraction of the time limit.
_H_MAX_FRACTION = 1e-3


@dataclass(frozen=True)
class _Model:
    """A dynamic model's id in the compiled model table and where its rate k sits in ``p``."""

    id: int
    k_index: int


PRESLIDING = _Model(MODEL_PRESLIDING, _P_K)
LUGRE = _Model(MODEL_LUGRE, _L_K)
LOOP_PRESLIDING = _Model(MODEL_LOOP_PRESLIDING, _P_K)
LOOP_LUGRE = _Model(MODEL_LOOP_LUGRE, _L_K)


def _check_rtol(rtol):
    check_positive(rtol=rtol)
    if not MIN_RTOL <= rtol <= 1e-3:
        raise ValueError(f"rtol must be in [{MIN_RTOL}, 1e-3], got {rtol}")


def _run_sweep(model, ks, p, y0, mem0, t_end, atols, rtol, max_steps):
    t_ba, F_ba, status, jumps = _sweep(model.id, y0, mem0, p, model.k_index, ks, t_end, rtol,
                                       atols, _H_MAX_FRACTION, max_steps)
    return RampBreakaway(ks, ks * t_ba, F_ba, t_ba, jumps)


def _new_record(capacity, n_states, n_memory):
    """Empty record arrays ``(t, y, F, mem, code)`` for ``capacity`` samples."""
    return (np.empty(capacity), np.empty((capacity, n_states)), np.empty(capacity),
            np.empty((capacity, n_memory)), np.empty(capacity, dtype=np.int64))


def _run_one(model, k, p, y0, mem0, t_end, atol, rtol, max_steps, capacity):
    p = p.copy()
    p[model.k_index] = k
    y, mem = y0.copy(), mem0.copy()
    rec = _new_record(capacity, y.size, mem.size)
    status, t, F, n, jumps = _integrate(model.id, y, mem, p, t_end, rtol, atol,
                                        t_end * _H_MAX_FRACTION, max_steps, rec, 0, -1)
    rec_t, rec_y, rec_F = rec[0][:n], rec[1][:n], rec[2][:n]
    broke = status == STATUS_BREAKAWAY
    return Trajectory(rec_t, rec_y[:, 0], rec_y[:, 1], rec_F, k * rec_t,
                      t if broke else np.nan, F if broke else np.nan, int(jumps),
                      rec_y[:, 2].copy() if y.size > 2 else None)


@dataclass(frozen=True)
class Recording:
    """A run recorded on an output grid plus selected events.

    Attributes
    ----------
    t, y, F, mem, code : numpy.ndarray
        Time [s], state, friction [N], discrete memory and event code (0 for a grid
        sample) of each recorded sample, in time order.
    t_end : float
        Where the run ended [s]: the requested end, or earlier when the step budget ran
        out or the model's stop fired.
    stopped : bool
        Whether the model's stop fired.
    jumps : int
        Guard crossings (events) of the whole run, recorded or not.
    """

    t: np.ndarray
    y: np.ndarray
    F: np.ndarray
    mem: np.ndarray
    code: np.ndarray
    t_end: float
    stopped: bool
    jumps: int


def _run_grid(model_id, p, y0, mem0, t_end, atol, rtol, max_steps, n_grid, event_mask,
              event_capacity):
    """One run from t = 0 to ``t_end`` recorded on ``n_grid`` uniform samples plus at
    most ``event_capacity`` events whose code shares a bit with ``event_mask``; returns
    the :class:`Recording` and the memory at the end."""
    y, mem = y0.copy(), mem0.copy()
    rec = _new_record(n_grid + event_capacity, y.size, mem.size)
    status, t, _, n, jumps = _integrate(model_id, y, mem, p, t_end, rtol, atol,
                                        t_end * _H_MAX_FRACTION, max_steps, rec, n_grid,
                                        event_mask)
    return Recording(*(a[:n] for a in rec), t_end=t, stopped=status == STATUS_BREAKAWAY,
                     jumps=int(jumps)), mem


@dataclass(frozen=True)
class LoopRun:
    """One run of the position loop on its output grid plus events.

    Attributes
    ----------
    t, x, v, u, F, r, e : numpy.ndarray
        Time [s], position [m], velocity [m/s], control force [N], friction [N],
        reference [m] and error r − x [m] per sample.
    code : numpy.ndarray
        Event code per sample (:mod:`.common`): 0 on the output grid, else the bits of
        the break-away or stick-phase start recorded there.
    t_end : float
        Where the run ended [s]: the requested duration, or earlier when the step budget
        ran out or the loop ran away.
    runaway : bool
        Whether the loop ran away (``|e|`` beyond the bound of :mod:`.loop_model`): unstable.
    reversals : int
        Changes of sign of ẋ over the run.
    """

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    u: np.ndarray
    F: np.ndarray
    r: np.ndarray
    e: np.ndarray
    code: np.ndarray
    t_end: float
    runaway: bool
    reversals: int
