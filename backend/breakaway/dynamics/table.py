"""The model table of the one integrator: every dynamic model's ``rhs``, ``force``,
``guard``, ``jump`` and ``stop`` (see :mod:`breakaway.dynamics`), dispatched on the
model id inside compiled code, because numba cannot cache functions that receive
jitted functions as arguments.
"""

from __future__ import annotations

from numba import njit

from .loop_model import (_loop_lugre_force, _loop_lugre_guard, _loop_lugre_jump,
                         _loop_lugre_rhs, _loop_presliding_force, _loop_presliding_guard,
                         _loop_presliding_jump, _loop_presliding_rhs, _loop_stop)
from .lugre import _lugre_force, _lugre_guard, _lugre_jump, _lugre_rhs, _lugre_stop
from .ramp_model import (_presliding_force, _presliding_guard, _presliding_jump,
                         _presliding_rhs, _presliding_stop)

#: the ramp experiment (E7) with (E6'), LuGre under the same ramp, and the position
#: loop with either friction model
MODEL_PRESLIDING, MODEL_LUGRE, MODEL_LOOP_PRESLIDING, MODEL_LOOP_LUGRE = 0, 1, 2, 3


@njit(cache=True)
def _rhs(model, t, y, p, mem, dy):
    if model == MODEL_PRESLIDING:
        _presliding_rhs(t, y, p, mem, dy)
    elif model == MODEL_LUGRE:
        _lugre_rhs(t, y, p, mem, dy)
    elif model == MODEL_LOOP_PRESLIDING:
        _loop_presliding_rhs(t, y, p, mem, dy)
    else:
        _loop_lugre_rhs(t, y, p, mem, dy)


@njit(cache=True)
def _force(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        return _presliding_force(t, y, p, mem)
    if model == MODEL_LUGRE:
        return _lugre_force(t, y, p, mem)
    if model == MODEL_LOOP_PRESLIDING:
        return _loop_presliding_force(t, y, p, mem)
    return _loop_lugre_force(t, y, p, mem)


@njit(cache=True)
def _guard(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        return _presliding_guard(t, y, p, mem)
    if model == MODEL_LUGRE:
        return _lugre_guard(t, y, p, mem)
    if model == MODEL_LOOP_PRESLIDING:
        return _loop_presliding_guard(t, y, p, mem)
    return _loop_lugre_guard(t, y, p, mem)


@njit(cache=True)
def _jump(model, t, y, p, mem):
    """Update ``mem`` at a guard crossing; returns the event code (a bit mask of
    :data:`~.loop_model.EVENT_REVERSAL` and the loop's other events)."""
    if model == MODEL_PRESLIDING:
        return _presliding_jump(t, y, p, mem)
    if model == MODEL_LUGRE:
        return _lugre_jump(t, y, p, mem)
    if model == MODEL_LOOP_PRESLIDING:
        return _loop_presliding_jump(t, y, p, mem)
    return _loop_lugre_jump(t, y, p, mem)


@njit(cache=True)
def _stop(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        return _presliding_stop(t, y, p, mem)
    if model == MODEL_LUGRE:
        return _lugre_stop(t, y, p, mem)
    return _loop_stop(t, y, p, mem)


@njit(cache=True)
def _stop_rises_between_jumps(model):
    """Whether the stop function can only rise until the next jump: then one check at
    the end of the interval replaces the scan. True for the presliding model, whose
    ``s·|x − x_r|`` grows while ẋ keeps its sign, and for the loops, which never stop;
    LuGre's −dF/dt has no such order."""
    return model != MODEL_LUGRE
