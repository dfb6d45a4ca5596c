"""Dynamic simulation of the ramp experiment (E7) and of the LuGre comparison model.

Both models are written with one signature (python-control's ``nlsys`` idea) and
integrated in one place, :func:`_integrate`:

- ``rhs(t, y, p, mem, dy)`` writes the state derivative ``dy``;
- ``force(t, y, p, mem)`` returns the friction force F [N];
- ``guard(t, y, p, mem)``: a sign change from ``>= 0`` to ``< 0`` calls
  ``jump(t, y, p, mem)``, which updates the discrete memory ``mem`` in place
  (a motion reversal starting a new presliding branch);
- ``stop(t, y, p, mem)``: a change from ``< 0`` to ``>= 0`` ends the run
  (break-away).

``p`` holds the parameters (the rate ``k`` included) and ``mem`` the discrete state.
The integrator is an adaptive Dormand–Prince 5(4) scheme compiled with numba. Each
accepted step's cubic Hermite interpolant is scanned for events, which are then located
by bisection, so a short excursion inside one step is not missed, and the step restarts
exactly at a reversal (a change of sign of ẋ starts a new branch at the current x and
F, MODEL.md §5). The models are selected by id inside compiled code (a small model
table) because numba cannot cache functions that receive jitted functions as arguments.

With velocity weakening the quasi-static branch of (E12) is unstable: the body chatters
through many reversals before it breaks away, and at small rates the break-away
becomes sensitive to round-off (a chaotic transient). There the result is defined only
to the scatter between tolerances, which the tests and the benchmark measure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .params import DEFAULTS, LUGRE_1995, _finite, check_fraction, check_positive, check_stribeck
from .presliding import shape_scalar

# ---------------------------------------------------------------------------------
# shared model pieces
# ---------------------------------------------------------------------------------


@njit(cache=True)
def _g(v, Fc, Fs, V, delta):
    """g(v) of (E2) for a scalar v, with the limits of MODEL.md §2 at v = 0."""
    av = abs(v)
    if av == 0.0:
        return Fs if delta > 0 else Fc
    return Fc + (Fs - Fc) * math.exp(-((av / V) ** delta))


@njit(cache=True)
def _dg_dabs(v, Fc, Fs, V, delta):
    """dg/d|v| for a scalar v (0 at v = 0 for δ >= 1)."""
    av = abs(v)
    if av == 0.0:
        return 0.0
    r = (av / V) ** delta
    return -(Fs - Fc) * delta * r / av * math.exp(-r)


# ---------------------------------------------------------------------------------
# the note's presliding model (E6') under the ramp u = k t (E7)
#   y = [x, v]; mem = [x_r, F_r, d]; p = [Fc, Fs, V, delta, sigma, s, m, k, z_ba]
# ---------------------------------------------------------------------------------
_P_FC, _P_FS, _P_V, _P_DELTA, _P_SIGMA, _P_S, _P_M, _P_K, _P_ZBA = range(9)


@njit(cache=True)
def _presliding_force(t, y, p, mem):
    z = p[_P_S] * abs(y[0] - mem[0])
    shape = shape_scalar(z)
    target = mem[2] * _g(y[1], p[_P_FC], p[_P_FS], p[_P_V], p[_P_DELTA]) + p[_P_SIGMA] * y[1]
    return mem[1] + (target - mem[1]) * shape


@njit(cache=True)
def _presliding_rhs(t, y, p, mem, dy):
    dy[0] = y[1]
    dy[1] = (p[_P_K] * t - _presliding_force(t, y, p, mem)) / p[_P_M]


@njit(cache=True)
def _presliding_guard(t, y, p, mem):
    return y[1] * mem[2]


@njit(cache=True)
def _presliding_jump(t, y, p, mem):
    # a change of sign of ẋ: new branch at the current x and F
    F = _presliding_force(t, y, p, mem)
    mem[0] = y[0]
    mem[1] = F
    mem[2] = -mem[2]


@njit(cache=True)
def _presliding_stop(t, y, p, mem):
    if mem[2] > 0:
        return p[_P_S] * abs(y[0] - mem[0]) - p[_P_ZBA]
    return -1.0


# ---------------------------------------------------------------------------------
# LuGre (Canudas de Wit et al. 1995) under the same ramp
#   y = [x, v, z]; mem unused; p = [sigma0, sigma1, sigma2, Fc, Fs, vs, delta, m, k]
# ---------------------------------------------------------------------------------
_L_S0, _L_S1, _L_S2, _L_FC, _L_FS, _L_VS, _L_DELTA, _L_M, _L_K = range(9)


@njit(cache=True)
def _lugre_zdot(y, p):
    g = _g(y[1], p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])
    return y[1] - p[_L_S0] * abs(y[1]) * y[2] / g


@njit(cache=True)
def _lugre_force(t, y, p, mem):
    return p[_L_S0] * y[2] + p[_L_S1] * _lugre_zdot(y, p) + p[_L_S2] * y[1]


@njit(cache=True)
def _lugre_rhs(t, y, p, mem, dy):
    dy[0] = y[1]
    dy[1] = (p[_L_K] * t - _lugre_force(t, y, p, mem)) / p[_L_M]
    dy[2] = _lugre_zdot(y, p)


@njit(cache=True)
def _lugre_guard(t, y, p, mem):
    return 1.0


@njit(cache=True)
def _lugre_jump(t, y, p, mem):
    pass


@njit(cache=True)
def _lugre_stop(t, y, p, mem):
    """−dF/dt: its first crossing to >= 0 is the first local maximum of F."""
    v, zb = y[1], y[2]
    a = (p[_L_K] * t - _lugre_force(t, y, p, mem)) / p[_L_M]
    g = _g(v, p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])
    av = abs(v)
    zdot = v - p[_L_S0] * av * zb / g
    # d/dt (|v|/g(v)) = sgn(v)·a·(g − |v|·dg/d|v|)/g²
    ratio_dot = math.copysign(1.0, v) * a * (g - av * _dg_dabs(v, p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])) / (g * g)
    if av == 0.0:
        ratio_dot = abs(a) / g
    zddot = a - p[_L_S0] * (ratio_dot * zb + av / g * zdot)
    return -(p[_L_S0] * zdot + p[_L_S1] * zddot + p[_L_S2] * a)


# ---------------------------------------------------------------------------------
# the model table: one signature, dispatched on the model id inside compiled code
# (jitted functions passed as arguments cannot be cached on disk by numba)
# ---------------------------------------------------------------------------------
MODEL_PRESLIDING, MODEL_LUGRE = 0, 1


@njit(cache=True)
def _rhs(model, t, y, p, mem, dy):
    if model == MODEL_PRESLIDING:
        _presliding_rhs(t, y, p, mem, dy)
    else:
        _lugre_rhs(t, y, p, mem, dy)


@njit(cache=True)
def _force(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        return _presliding_force(t, y, p, mem)
    return _lugre_force(t, y, p, mem)


@njit(cache=True)
def _guard(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        return _presliding_guard(t, y, p, mem)
    return _lugre_guard(t, y, p, mem)


@njit(cache=True)
def _jump(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        _presliding_jump(t, y, p, mem)
    else:
        _lugre_jump(t, y, p, mem)


@njit(cache=True)
def _stop(model, t, y, p, mem):
    if model == MODEL_PRESLIDING:
        return _presliding_stop(t, y, p, mem)
    return _lugre_stop(t, y, p, mem)


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
def _stop_rises_between_jumps(model):
    """Whether the stop function can only rise until the next jump: then one check at
    the end of the interval replaces the scan. True for the presliding model, whose
    ``s·|x − x_r|`` grows while ẋ keeps its sign; LuGre's −dF/dt has no such order."""
    return model == MODEL_PRESLIDING


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
def _record(model, rec_t, rec_y, rec_F, n_rec, t, y, p, mem):
    """Store one sample while the record arrays have room (the force is evaluated only
    then: a sweep records nothing); returns the new count."""
    if n_rec < rec_t.size:
        rec_t[n_rec] = t
        rec_y[n_rec, :] = y
        rec_F[n_rec] = _force(model, t, y, p, mem)
        n_rec += 1
    return n_rec


@njit(cache=True)
def _integrate(model, y0, mem, p, t_end, rtol, atol, h_max, max_steps, rec_t, rec_y, rec_F):
    """Integrate from t = 0 until ``stop`` fires, ``t_end`` or ``max_steps``.

    Returns ``(status, t, F, n_recorded, n_jumps)``; the final state is left in ``y0``.
    Each accepted step (and each event) is recorded while ``rec_t`` has room.
    """
    n = y0.size
    y = y0
    k1 = np.empty(n); k2 = np.empty(n); k3 = np.empty(n); k4 = np.empty(n)
    k5 = np.empty(n); k6 = np.empty(n); k7 = np.empty(n)
    ytmp = np.empty(n); ynew = np.empty(n); work = np.empty(n)
    t = 0.0
    h = min(h_max, t_end * 1e-6)
    _rhs(model, t, y, p, mem, k1)
    n_rec = 0
    n_jumps = 0
    n_rec = _record(model, rec_t, rec_y, rec_F, n_rec, t, y, p, mem)
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
            h *= max(0.2, 0.9 * norm ** -0.2) if norm == norm else 0.2
            continue
        # accepted step [t, t + h]: the earlier of break-away and reversal wins
        theta_jump = _first_crossing(model, _EVENT_GUARD, t, y, k1, ynew, k7, h, p, mem, ytmp,
                                     1.0, True)
        # only a break-away before the reversal counts
        theta_end = theta_jump if theta_jump >= 0 else 1.0
        theta_stop = _first_crossing(model, _EVENT_STOP, t, y, k1, ynew, k7, h, p, mem, work,
                                     theta_end, not _stop_rises_between_jumps(model))
        if theta_stop >= 0:
            t_stop = t + theta_stop * h
            y[:] = work
            F = _force(model, t_stop, y, p, mem)
            n_rec = _record(model, rec_t, rec_y, rec_F, n_rec, t_stop, y, p, mem)
            return STATUS_BREAKAWAY, t_stop, F, n_rec, n_jumps
        if theta_jump >= 0:
            t = t + theta_jump * h
            y[:] = ytmp
            n_rec = _record(model, rec_t, rec_y, rec_F, n_rec, t, y, p, mem)
            _jump(model, t, y, p, mem)
            n_jumps += 1
            _rhs(model, t, y, p, mem, k1)
            # the new branch starts with an infinite presliding stiffness: restart small
            h = max(h * 1e-3, 1e-14 * max(t, 1.0))
            continue
        t += h
        y[:] = ynew
        k1[:] = k7
        n_rec = _record(model, rec_t, rec_y, rec_F, n_rec, t, y, p, mem)
        h *= min(5.0, 0.9 * max(norm, 1e-10) ** -0.2)
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
    no_t = np.empty(0)
    no_y = np.empty((0, y0.size))
    for j in range(nk):
        pj = p.copy()
        pj[k_index] = ks[j]
        y = y0.copy()
        mem = mem0.copy()
        st, t, F, _, nj = _integrate(model, y, mem, pj, t_ends[j], rtol, atols[j],
                                     t_ends[j] * h_max_frac, max_steps, no_t, no_y, no_t)
        status[j] = st
        t_ba[j] = t if st == STATUS_BREAKAWAY else np.nan
        F_ba[j] = F if st == STATUS_BREAKAWAY else np.nan
        jumps[j] = nj
    return t_ba, F_ba, status, jumps


# ---------------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------------


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


def _rates(k):
    k = np.atleast_1d(np.asanyarray(k, dtype=float)).ravel()
    if k.size == 0 or np.any(~np.isfinite(k)) or np.any(k <= 0):
        raise ValueError("k must be a non-empty list of finite rates > 0")
    return k


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


def _check_rtol(rtol):
    check_positive(rtol=rtol)
    if not MIN_RTOL <= rtol <= 1e-3:
        raise ValueError(f"rtol must be in [{MIN_RTOL}, 1e-3], got {rtol}")


def _presliding_problem(ks, Fc, Fs, V, delta, s, sigma, m, z_ba, rtol):
    """Parameters, initial state, memory, time limits and tolerances per rate."""
    check_stribeck(Fc, Fs, V, delta, sigma)
    check_positive(s=s, m=m)
    _check_rtol(rtol)
    check_fraction("z_ba", z_ba)
    p = np.array([Fc, Fs, V, delta, sigma, s, m, 0.0, z_ba], dtype=float)
    y0 = np.zeros(2)
    mem0 = np.array([0.0, 0.0, 1.0])  # virgin state: x_r = 0, F_r = 0, d = +1
    # quasi-static time to reach the steady level, or the time the ramp alone needs
    # to push the mass across the presliding distance, whichever is longer
    t_end = 20.0 * (max(Fs, Fc) / ks + (6.0 * m / (s * ks)) ** (1.0 / 3.0))
    # absolute tolerances: x against 1/s, v against the E12 velocity k/(s·Fc)
    atols = 1e-3 * rtol * np.column_stack([np.full(ks.size, 1.0 / s), ks / (s * Fc)])
    return p, y0, mem0, t_end, atols


def _lugre_problem(ks, params, rtol):
    _check_rtol(rtol)
    unknown = sorted(set(params or {}) - set(LUGRE_1995))
    if unknown:
        raise ValueError(f"unknown LuGre parameter(s) {unknown}; known: {sorted(LUGRE_1995)}")
    q = {**LUGRE_1995, **(params or {})}
    # the LuGre names first (vs, sigma2), then (E2)'s remaining constraints
    check_positive(vs=q["vs"], sigma0=q["sigma0"], m=q["m"])
    for name in ("sigma1", "sigma2"):
        if _finite(name, q[name]) < 0:
            raise ValueError(f"{name} must be >= 0, got {q[name]}")
    check_stribeck(q["Fc"], q["Fs"], q["vs"], q["delta"], q["sigma2"])
    p = np.array([q["sigma0"], q["sigma1"], q["sigma2"], q["Fc"], q["Fs"], q["vs"],
                  q["delta"], q["m"], 0.0])
    bristle = q["Fs"] / q["sigma0"]  # bristle deflection at stiction [m]
    s = 1.0 / bristle
    t_end = 20.0 * (q["Fs"] / ks + (6.0 * q["m"] / (s * ks)) ** (1.0 / 3.0))
    v_scale = np.maximum(ks / (s * q["Fc"]), q["vs"])
    atols = 1e-3 * rtol * np.column_stack([np.full(ks.size, bristle), v_scale,
                                           np.full(ks.size, bristle)])
    return p, np.zeros(3), np.zeros(1), t_end, atols


def _run_sweep(model, ks, p, y0, mem0, t_end, atols, rtol, max_steps):
    t_ba, F_ba, status, jumps = _sweep(model.id, y0, mem0, p, model.k_index, ks, t_end, rtol,
                                       atols, _H_MAX_FRACTION, max_steps)
    return RampBreakaway(ks, ks * t_ba, F_ba, t_ba, jumps)


def _run_one(model, k, p, y0, mem0, t_end, atol, rtol, max_steps, capacity):
    p = p.copy()
    p[model.k_index] = k
    y, mem = y0.copy(), mem0.copy()
    rec_t, rec_y, rec_F = np.empty(capacity), np.empty((capacity, y.size)), np.empty(capacity)
    status, t, F, n, jumps = _integrate(model.id, y, mem, p, t_end, rtol, atol,
                                        t_end * _H_MAX_FRACTION, max_steps, rec_t, rec_y, rec_F)
    broke = status == STATUS_BREAKAWAY
    return Trajectory(rec_t[:n], rec_y[:n, 0], rec_y[:n, 1], rec_F[:n], k * rec_t[:n],
                      t if broke else np.nan, F if broke else np.nan, int(jumps),
                      rec_y[:n, 2].copy() if y.size > 2 else None)


def simulate_breakaway(k, Fc, Fs, V, delta, s=1.0, sigma=0.0, m=DEFAULTS["m"], z_ba=0.95,
                       rtol=DEFAULT_RTOL, max_steps=2_000_000):
    """Break-away of the ramp experiment ``m·ẍ + F = k·t`` (E7) for each rate.

    Starts at rest in the virgin presliding state; F follows (E6') with exact reversal
    handling. Break-away is the first time ``s·|x − x_r| >= z*`` with ``d = +1``
    (MODEL.md §5).

    Parameters
    ----------
    k : array_like
        Actuation force rates [N/s], each > 0.
    Fc, Fs, V, delta, sigma :
        Steady-state parameters (E2), units as in :mod:`breakaway.steady`.
    s : float, optional
        Presliding scale [1/m].
    m : float, optional
        Moving mass [kg].
    z_ba : float, optional
        Presliding fraction taken as break-away [-].
    rtol : float, optional
        Relative tolerance of the adaptive integrator.
    max_steps : int, optional
        Step budget per rate; a rate that exhausts it reports NaN.

    Returns
    -------
    RampBreakaway
        ``u_ba = k·t_ba`` [N], ``F_ba`` [N], ``t_ba`` [s] per rate.
    """
    ks = _rates(k)
    p, y0, mem0, t_end, atols = _presliding_problem(ks, Fc, Fs, V, delta, s, sigma, m, z_ba,
                                                    rtol)
    return _run_sweep(PRESLIDING, ks, p, y0, mem0, t_end, atols, rtol, max_steps)


def simulate_trajectory(k, Fc, Fs, V, delta, s=1.0, sigma=0.0, m=DEFAULTS["m"], z_ba=0.95,
                        rtol=DEFAULT_RTOL, max_steps=2_000_000, capacity=200_000):
    """One ramp run of (E7) up to break-away, recorded at every step and reversal.

    Parameters are those of :func:`simulate_breakaway` with a single rate ``k`` [N/s];
    ``capacity`` bounds the number of recorded samples.

    Returns
    -------
    Trajectory
    """
    ks = _rates(k)
    if ks.size != 1:
        raise ValueError("k must be a single rate")
    p, y0, mem0, t_end, atols = _presliding_problem(ks, Fc, Fs, V, delta, s, sigma, m, z_ba,
                                                    rtol)
    return _run_one(PRESLIDING, ks[0], p, y0, mem0, t_end[0], atols[0], rtol, max_steps,
                    capacity)


def simulate_lugre_breakaway(k, params=None, rtol=DEFAULT_RTOL, max_steps=2_000_000):
    """Break-away of the LuGre model under the ramp ``u = k·t``: the first local max of F.

    Parameters
    ----------
    k : array_like
        Actuation force rates [N/s].
    params : dict, optional
        Overrides of :data:`breakaway.params.LUGRE_1995` (``sigma0`` [N/m], ``sigma1``
        [N s/m], ``sigma2`` [N s/m], ``Fc``, ``Fs`` [N], ``vs`` [m/s], ``delta``, ``m`` [kg]).
    rtol : float, optional
        Relative tolerance.

    Returns
    -------
    RampBreakaway
        ``F_ba`` is the first local maximum of F, ``u_ba = k·t`` at that instant.
    """
    ks = _rates(k)
    p, y0, mem0, t_end, atols = _lugre_problem(ks, params, rtol)
    return _run_sweep(LUGRE, ks, p, y0, mem0, t_end, atols, rtol, max_steps)


def simulate_lugre_trajectory(k, params=None, rtol=DEFAULT_RTOL, max_steps=2_000_000,
                              capacity=200_000):
    """One LuGre ramp run up to the first local maximum of F (see :func:`simulate_lugre_breakaway`)."""
    ks = _rates(k)
    if ks.size != 1:
        raise ValueError("k must be a single rate")
    p, y0, mem0, t_end, atols = _lugre_problem(ks, params, rtol)
    return _run_one(LUGRE, ks[0], p, y0, mem0, t_end[0], atols[0], rtol, max_steps, capacity)
