"""The one integrator of the dynamic models: an adaptive Dormand–Prince 5(4) scheme
compiled with numba, with event location on each step's Hermite interpolant, exact
restarts at reversals, and a sweep over rates (see :mod:`breakaway.dynamics`; the
Python side of a run is :mod:`.runs`).

The models are selected by id inside compiled code (:mod:`.table`) because numba
cannot cache functions that receive jitted functions as arguments.

A run records either every accepted step and event (the ramp), or a uniform output
grid, interpolated on each step's Hermite cubic, plus the events a mask selects (the
loop: a plot needs a few thousand samples, not every step through a chattering stick).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .common import EVENT_REVERSAL
from .table import _force, _guard, _jump, _rhs, _stop, _stop_rises_between_jumps

# ---------------------------------------------------------------------------------
# the one integrator
# ---------------------------------------------------------------------------------
# Dormand–Prince 5(4) tableau
_C2, _C3, _C4, _C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
_A21 = 1 / 5
_A31, _A32 = 3 / 40, 9 / 40
_A41, _A42, _A43 = 44 / 45, -56 / 15, 32 / 9
_A51, _A52, _A53, _A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
_A61, _A62, _A63, _A64, _A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
_B1, _B3, _B4, _B5, _B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
_E1, _E3, _E4, _E5, _E6, _E7 = (71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200,
                                22 / 525, -1 / 40)

STATUS_BREAKAWAY, STATUS_TIMEOUT, STATUS_STEP_LIMIT = 0, 1, 2


@njit(cache=True)
def _hermite(y0, f0, y1, f1, h, theta, out):
    t2 = theta * theta
    t3 = t2 * theta
    h00 = 2 * t3 - 3 * t2 + 1
    h10 = t3 - 2 * t2 + theta
    h01 = -2 * t3 + 3 * t2
    h11 = t3 - t2
    for i in range(y0.size):
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@njit(cache=True)
def _step_factor(norm):
    """norm^(-1/5), the step's change for an error ``norm`` of the 4th-order estimate,
    as exp and log, as the page's integrator.js computes it (V8's pow is slow)."""
    return math.exp(-0.2 * math.log(norm))


#: Points at which each accepted step's interpolant is scanned for sign changes, so a
#: short excursion (two reversals inside one step) is not stepped over.
_SCAN_POINTS = 4


@njit(cache=True)
def _event(model, which, t, y, p, mem):
    if which == _EVENT_STOP:
        return -_stop(model, t, y, p, mem)
    return _guard(model, t, y, p, mem)


_EVENT_STOP, _EVENT_GUARD = 0, 1


@njit(cache=True)
def _first_crossing(model, which, t0, y0, f0, y1, f1, h, p, mem, work, theta_max, scan):
    """First θ in (0, ``theta_max``] where event ``which`` fires along the step's
    interpolant.

    The event value (the guard, or minus the stop function) passing from >= 0 to < 0
    fires. With ``scan`` the interpolant is checked at :data:`_SCAN_POINTS` points (an
    excursion inside the step is not missed); without, only at ``theta_max`` (for an
    event value that is monotone there). Returns -1 when there is none; on success the
    interpolated state at the returned θ (the far side of the crossing) is left in
    ``work``.
    """
    lo = 0.0
    if _event(model, which, t0, y0, p, mem) < 0:
        return -1.0
    points = _SCAN_POINTS if scan else 1
    for j in range(1, points + 1):
        hi = theta_max * j / points
        if hi == 1.0:
            work[:] = y1
        else:
            _hermite(y0, f0, y1, f1, h, hi, work)
        if _event(model, which, t0 + hi * h, work, p, mem) < 0:
            break
        lo = hi
    else:
        return -1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        _hermite(y0, f0, y1, f1, h, mid, work)
        if _event(model, which, t0 + mid * h, work, p, mem) >= 0:
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-15:
            break
    _hermite(y0, f0, y1, f1, h, hi, work)
    return hi


@njit(cache=True)
def _record(model, rec, n_rec, t, y, p, mem, code):
    """Store one sample (t, y, F, mem and the event ``code``, 0 for none) in the record
    ``rec = (t, y, F, mem, code)`` while it has room (the force is evaluated only then:
    a sweep records nothing); returns the new count."""
    rec_t, rec_y, rec_F, rec_mem, rec_code = rec
    if n_rec < rec_t.size:
        rec_t[n_rec] = t
        rec_y[n_rec, :] = y
        rec_F[n_rec] = _force(model, t, y, p, mem)
        rec_mem[n_rec, :] = mem
        rec_code[n_rec] = code
        n_rec += 1
    return n_rec


@njit(cache=True)
def _record_grid(model, rec, n_rec, j, n_grid, t_end, t0, y0, f0, y1, f1, h, theta, p, mem,
                 work):
    """Record the output grid's samples ``t_end·j/(n_grid − 1)`` that fall in the
    accepted part ``(t0, t0 + θ·h]`` of a step, interpolated; returns (n_rec, next j)."""
    t1 = t0 + theta * h
    while j < n_grid:
        t_grid = t_end * j / (n_grid - 1)
        if t_grid > t1:
            break
        _hermite(y0, f0, y1, f1, h, (t_grid - t0) / h, work)
        n_rec = _record(model, rec, n_rec, t_grid, work, p, mem, 0)
        j += 1
    return n_rec, j


@njit(cache=True)
def _integrate(model, y0, mem, p, t_end, rtol, atol, h_max, max_steps, rec, n_grid=0,
               event_mask=-1):
    """Integrate from t = 0 until ``stop`` fires, ``t_end`` or ``max_steps``.

    Returns ``(status, t, F, n_recorded, n_jumps)``; the final state is left in ``y0``.
    With ``n_grid = 0`` each accepted step and each event is recorded in ``rec`` (see
    :func:`_record`) while it has room; with ``n_grid >= 2`` the uniform grid of
    ``n_grid`` times over [0, t_end] is, and the events whose code shares a bit with
    ``event_mask`` while the room beyond the grid lasts. An event is recorded after its jump (the new branch's memory; x, ẋ
    and the presliding force are continuous across it).
    """
    n = y0.size
    y = y0
    k1 = np.empty(n); k2 = np.empty(n); k3 = np.empty(n); k4 = np.empty(n)
    k5 = np.empty(n); k6 = np.empty(n); k7 = np.empty(n)
    ytmp = np.empty(n); ynew = np.empty(n); work = np.empty(n); grid_work = np.empty(n)
    t = 0.0
    h = min(h_max, t_end * 1e-6)
    _rhs(model, t, y, p, mem, k1)
    n_rec = 0
    n_jumps = 0
    n_rec = _record(model, rec, n_rec, t, y, p, mem, 0)
    j_grid = 1  # the next grid sample (t = 0 is recorded)
    every_step = n_grid == 0
    event_room = rec[0].size - n_grid  # events never take a grid sample's place
    for _ in range(max_steps):
        if t >= t_end:
            return STATUS_TIMEOUT, t, _force(model, t, y, p, mem), n_rec, n_jumps
        h = min(h, h_max, t_end - t)
        for i in range(n):
            ytmp[i] = y[i] + h * _A21 * k1[i]
        _rhs(model, t + _C2 * h, ytmp, p, mem, k2)
        for i in range(n):
            ytmp[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        _rhs(model, t + _C3 * h, ytmp, p, mem, k3)
        for i in range(n):
            ytmp[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        _rhs(model, t + _C4 * h, ytmp, p, mem, k4)
        for i in range(n):
            ytmp[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        _rhs(model, t + _C5 * h, ytmp, p, mem, k5)
        for i in range(n):
            ytmp[i] = y[i] + h * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i]
                                  + _A65 * k5[i])
        _rhs(model, t + h, ytmp, p, mem, k6)
        for i in range(n):
            ynew[i] = y[i] + h * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i]
                                  + _B6 * k6[i])
        _rhs(model, t + h, ynew, p, mem, k7)
        norm = 0.0
        for i in range(n):
            e = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i]
                     + _E7 * k7[i])
            scale = atol[i] + rtol * max(abs(y[i]), abs(ynew[i]))
            norm += (e / scale) ** 2
        norm = math.sqrt(norm / n)
        if not (norm <= 1.0):
            h *= max(0.2, 0.9 * _step_factor(norm)) if norm == norm else 0.2
            continue
        # accepted step [t, t + h]: the earlier of break-away and reversal wins
        theta_jump = _first_crossing(model, _EVENT_GUARD, t, y, k1, ynew, k7, h, p, mem, ytmp,
                                     1.0, True)
        # only a break-away before the reversal counts
        theta_end = theta_jump if theta_jump >= 0 else 1.0
        theta_stop = _first_crossing(model, _EVENT_STOP, t, y, k1, ynew, k7, h, p, mem, work,
                                     theta_end, not _stop_rises_between_jumps(model))
        theta_done = theta_stop if theta_stop >= 0 else theta_end
        if not every_step:
            n_rec, j_grid = _record_grid(model, rec, n_rec, j_grid, n_grid, t_end, t, y, k1,
                                         ynew, k7, h, theta_done, p, mem, grid_work)
        if theta_stop >= 0:
            t_stop = t + theta_stop * h
            y[:] = work
            F = _force(model, t_stop, y, p, mem)
            n_rec = _record(model, rec, n_rec, t_stop, y, p, mem, 0)
            return STATUS_BREAKAWAY, t_stop, F, n_rec, n_jumps
        if theta_jump >= 0:
            t = t + theta_jump * h
            y[:] = ytmp
            code = _jump(model, t, y, p, mem)
            n_jumps += 1
            if every_step:
                n_rec = _record(model, rec, n_rec, t, y, p, mem, code)
            elif code & event_mask and event_room > 0:
                n_rec = _record(model, rec, n_rec, t, y, p, mem, code)
                event_room -= 1
            _rhs(model, t, y, p, mem, k1)
            if code & EVENT_REVERSAL:
                # the new branch starts with an infinite presliding stiffness: restart at a
                # tenth (a thousandth cost a fifth of a chattering loop's steps in regrowth)
                h = max(h * 0.1, 1e-14 * max(t, 1.0))
            continue
        t += h
        y[:] = ynew
        k1[:] = k7
        if every_step:
            n_rec = _record(model, rec, n_rec, t, y, p, mem, 0)
        h *= min(5.0, 0.9 * _step_factor(max(norm, 1e-10)))
    return STATUS_STEP_LIMIT, t, _force(model, t, y, p, mem), n_rec, n_jumps


@njit(cache=True)
def _sweep(model, y0, mem0, p, k_index, ks, t_ends, rtol, atols, h_max_frac, max_steps):
    """Run :func:`_integrate` for each rate ``ks[j]`` (tolerances ``atols[j]``).

    Returns t_ba, F_ba, status and the number of reversals per rate.
    """
    nk = ks.size
    t_ba = np.empty(nk)
    F_ba = np.empty(nk)
    status = np.empty(nk, dtype=np.int64)
    jumps = np.empty(nk, dtype=np.int64)
    nothing = (np.empty(0), np.empty((0, y0.size)), np.empty(0), np.empty((0, mem0.size)),
               np.empty(0, dtype=np.int64))
    for j in range(nk):
        pj = p.copy()
        pj[k_index] = ks[j]
        y = y0.copy()
        mem = mem0.copy()
        st, t, F, _, nj = _integrate(model, y, mem, pj, t_ends[j], rtol, atols[j],
                                     t_ends[j] * h_max_frac, max_steps, nothing, 0, -1)
        status[j] = st
        t_ba[j] = t if st == STATUS_BREAKAWAY else np.nan
        F_ba[j] = F if st == STATUS_BREAKAWAY else np.nan
        jumps[j] = nj
    return t_ba, F_ba, status, jumps
