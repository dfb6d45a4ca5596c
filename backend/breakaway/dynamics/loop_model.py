"""The position loop (PID control of m·ẍ + F = u) with either friction model: its compiled
right-hand side, force, guard and jump, and its problem set-up.

    m·ẍ + F(ẋ, z) = u,   u = Kp·e + Ki·∫e dt + Kd·(ṙ − ẋ) + c·F_m(ṙ),   e = r − x

clamped to |u| ≤ u_max when a limit is given. The integrator state is the plant's with
∫e appended, ``y = [x, v, ∫e]`` (E6') or ``[x, v, z, ∫e]`` (LuGre); ``p`` is the
plant's parameter vector of :mod:`.ramp_model` or :mod:`.lugre` (its rate ``k`` unused)
followed by the loop block ``_KP … _ZBA``; ``mem = [x_r, F_r, d, sr, broken, sticking,
reversals]``: the presliding memory (for LuGre only x_r and d are used), the branch
``sr`` of the compensation's sgn(ṙ), whether this branch has broken away, whether a
stick phase is running, and the count of reversals so far.

Events (a guard crossing, :mod:`.common`'s codes): a change of sign of ẋ starts a new
branch, and the first one after a break-away starts a stick phase; the presliding
fraction reaching z* on a branch is its break-away (E6': ``s·|x − x_r|``; LuGre: the
bristle's deflection as a fraction of its steady value, ``d·σ0·z/g(ẋ)``); a change of
sign of ṙ (sine reference) switches the compensation's branch, so that its jump
(−F_m to +F_m) falls on an event instead of inside a step.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..params import _finite, check_fraction, check_positive, check_stribeck
from .common import (EVENT_BREAKAWAY, EVENT_COMPENSATION, EVENT_REVERSAL, EVENT_STICK, _g,
                     _g_branch)
from .lugre import (_L_DELTA, _L_FC, _L_FS, _L_M, _L_S0, _L_VS, _lugre_force, _lugre_params,
                    _lugre_zdot)
from .ramp_model import _P_M, _P_S, _presliding_force, _presliding_params

#: the loop block of ``p``, after the plant's nine entries
(_KP, _KI, _KD, _UMAX, _C, _CFC, _CFS, _CV, _CDELTA, _CSIGMA, _REF, _H, _W, _FREQ,
 _ZBA, _RUNAWAY) = range(9, 25)
#: A run whose error exceeds this many times the reference's scale has run away (an
#: unstable loop): it ends there instead of spending its step budget on growth.
RUNAWAY_FACTOR = 100.0
_XR, _FR, _D, _SR, _BROKEN, _STICKING, _REVERSALS = range(7)
REFERENCES = ("step", "ramp", "sine")
_REF_STEP, _REF_RAMP, _REF_SINE = range(3)


@njit(cache=True)
def _reference(t, p):
    """r(t) [m] and ṙ(t) [m/s] of the step, ramp or sine reference."""
    kind = p[_REF]
    if kind == _REF_STEP:
        return p[_H], 0.0
    if kind == _REF_RAMP:
        return p[_W] * t, p[_W]
    omega = 2.0 * math.pi * p[_FREQ]
    return p[_H] * math.sin(omega * t), p[_H] * omega * math.cos(omega * t)


@njit(cache=True)
def _control(t, y, p, mem, r, r_dot):
    """The controller's force u [N] for the reference r, ṙ at t: PID with the
    derivative on ṙ − ẋ, plus c·F_m(ṙ) on the compensation's branch, clamped to ±u_max."""
    u = p[_KP] * (r - y[0]) + p[_KI] * y[y.size - 1] + p[_KD] * (r_dot - y[1])
    if p[_C] != 0.0 and mem[_SR] != 0.0:
        # F_m = Fss(ṙ) of (E2) with sgn(ṙ) held on its branch (sr = 0: ṙ ≡ 0, F_m = 0)
        g = _g_branch(mem[_SR] * r_dot, p[_CFC], p[_CFS], p[_CV], p[_CDELTA])
        u += p[_C] * (mem[_SR] * g + p[_CSIGMA] * r_dot)
    return min(max(u, -p[_UMAX]), p[_UMAX])


@njit(cache=True)
def _loop_rhs(t, y, p, mem, F, m, dy):
    """ẋ, ẍ = (u − F)/m and d∫e/dt = e; the plant's own states are the caller's."""
    r, r_dot = _reference(t, p)
    dy[0] = y[1]
    dy[1] = (_control(t, y, p, mem, r, r_dot) - F) / m
    dy[y.size - 1] = r - y[0]


@njit(cache=True)
def _loop_guard(fraction, t, y, p, mem):
    """min of: ẋ·d (reversal), ṙ·sr (compensation branch, sine only) and
    z* − fraction (break-away, until this branch has broken away)."""
    value = y[1] * mem[_D]
    if p[_REF] == _REF_SINE:
        value = min(value, _reference(t, p)[1] * mem[_SR])
    if mem[_BROKEN] == 0.0:
        value = min(value, p[_ZBA] - fraction)
    return value


@njit(cache=True)
def _loop_jump(fraction, F, t, y, p, mem):
    """Every crossing the guard saw: break-away (ends the stick phase), reversal (new
    branch at the current x and F; the first after a break-away starts a stick phase),
    compensation branch. Returns the event code."""
    code = 0
    if mem[_BROKEN] == 0.0 and fraction >= p[_ZBA]:
        mem[_BROKEN] = 1.0
        mem[_STICKING] = 0.0
        code |= EVENT_BREAKAWAY
    if y[1] * mem[_D] < 0:
        mem[_XR] = y[0]
        mem[_FR] = F
        mem[_D] = -mem[_D]
        mem[_BROKEN] = 0.0
        mem[_REVERSALS] += 1.0
        code |= EVENT_REVERSAL
        if mem[_STICKING] == 0.0:
            mem[_STICKING] = 1.0
            code |= EVENT_STICK
    if p[_REF] == _REF_SINE and _reference(t, p)[1] * mem[_SR] < 0:
        mem[_SR] = -mem[_SR]
        code |= EVENT_COMPENSATION
    return code


@njit(cache=True)
def _loop_stop(t, y, p, mem):
    """A loop runs to its end time unless |e| passes the runaway bound."""
    return abs(_reference(t, p)[0] - y[0]) - p[_RUNAWAY]


# -- (E6') in the loop ------------------------------------------------------------
@njit(cache=True)
def _presliding_fraction(y, p, mem):
    return p[_P_S] * abs(y[0] - mem[_XR])


@njit(cache=True)
def _loop_presliding_force(t, y, p, mem):
    return _presliding_force(t, y, p, mem)


@njit(cache=True)
def _loop_presliding_rhs(t, y, p, mem, dy):
    _loop_rhs(t, y, p, mem, _presliding_force(t, y, p, mem), p[_P_M], dy)


@njit(cache=True)
def _loop_presliding_guard(t, y, p, mem):
    return _loop_guard(_presliding_fraction(y, p, mem), t, y, p, mem)


@njit(cache=True)
def _loop_presliding_jump(t, y, p, mem):
    return _loop_jump(_presliding_fraction(y, p, mem), _presliding_force(t, y, p, mem),
                      t, y, p, mem)


# -- LuGre in the loop --------------------------------------------------------------
@njit(cache=True)
def _bristle_fraction(y, p, mem):
    """d·σ0·z/g(ẋ): the bristle's deflection as a fraction of its steady value."""
    g = _g(y[1], p[_L_FC], p[_L_FS], p[_L_VS], p[_L_DELTA])
    return mem[_D] * p[_L_S0] * y[2] / g


@njit(cache=True)
def _loop_lugre_force(t, y, p, mem):
    return _lugre_force(t, y, p, mem)


@njit(cache=True)
def _loop_lugre_rhs(t, y, p, mem, dy):
    _loop_rhs(t, y, p, mem, _lugre_force(t, y, p, mem), p[_L_M], dy)
    dy[2] = _lugre_zdot(y, p)


@njit(cache=True)
def _loop_lugre_guard(t, y, p, mem):
    return _loop_guard(_bristle_fraction(y, p, mem), t, y, p, mem)


@njit(cache=True)
def _loop_lugre_jump(t, y, p, mem):
    return _loop_jump(_bristle_fraction(y, p, mem), _lugre_force(t, y, p, mem), t, y, p, mem)


@njit(cache=True)
def _loop_outputs(t, y, mem, p):
    """r and u at recorded samples (t, y and the memory ``mem`` of each)."""
    n = t.size
    r, u = np.empty(n), np.empty(n)
    for i in range(n):
        r[i], r_dot = _reference(t[i], p)
        u[i] = _control(t[i], y[i], p, mem[i], r[i], r_dot)
    return r, u


# -- set-up -------------------------------------------------------------------------
def _nonnegative(name, value):
    if _finite(name, value) < 0:
        raise ValueError(f"{name} must be >= 0, got {value}")
    return float(value)


def loop_block(controller, reference, compensation, z_ba, runaway):
    """The loop block of ``p`` and the initial compensation branch ``sr``.

    ``controller``: Kp [N/m], Ki [N/(m·s)], Kd [N·s/m] (each >= 0), u_max [N] (> 0, or
    None for no limit); ``reference``: kind ('step', 'ramp', 'sine'), h [m] (step,
    sine), w [m/s] (ramp), f [Hz] (sine); ``compensation``: scale c (>= 0) and the
    F_m parameters Fc, Fs, V, delta, sigma of (E2); ``runaway``: the bound on |e| [m]
    that ends a run.
    """
    gains = [_nonnegative(name, controller[name]) for name in ("Kp", "Ki", "Kd")]
    u_max = controller.get("u_max")
    if u_max is not None:
        check_positive(u_max=u_max)
    kind = reference["kind"]
    if kind not in REFERENCES:
        raise ValueError(f"kind must be one of {REFERENCES}, got {kind!r}")
    h, w, f = (float(reference.get(name) or 0.0) for name in ("h", "w", "f"))
    if kind == "ramp":
        if _finite("w", w) == 0:
            raise ValueError("w must be non-zero for a ramp reference")
    elif _finite("h", h) == 0:
        raise ValueError(f"h must be non-zero for a {kind} reference")
    if kind == "sine":
        check_positive(f=f)
    c = _nonnegative("scale", compensation["scale"])
    m = compensation["params"]
    check_stribeck(m["Fc"], m["Fs"], m["V"], m["delta"], m["sigma"])
    block = [*gains, math.inf if u_max is None else float(u_max), c, m["Fc"], m["Fs"], m["V"],
             m["delta"], m["sigma"], REFERENCES.index(kind), h, w, f, z_ba, runaway]
    sr = {"step": 0.0, "ramp": math.copysign(1.0, w), "sine": math.copysign(1.0, h)}[kind]
    return np.array(block, dtype=float), sr


def plant_steady(model, params):
    """The plant's steady-state (E2) parameters Fc, Fs, V, delta, sigma (LuGre: vs is V,
    sigma2 is sigma), the compensation's default."""
    if model == "lugre":
        q = params
        return {"Fc": q["Fc"], "Fs": q["Fs"], "V": q["vs"], "delta": q["delta"],
                "sigma": q["sigma2"]}
    return {name: params[name] for name in ("Fc", "Fs", "V", "delta", "sigma")}


def loop_problem(model, params, controller, reference, compensation, duration, rtol):
    """``p``, y0, mem0 and the absolute tolerances of one loop run.

    ``params``: the presliding plant's Fc, Fs, V, delta, sigma, s, m, z_ba, or LuGre's
    overrides of ``LUGRE_1995`` plus z_ba; ``compensation``: ``{"scale", "params"}``
    with the F_m parameters (each omitted one is the plant's steady state's).
    The run ends early when |e| exceeds :data:`RUNAWAY_FACTOR` times the reference's
    scale (|h|, or |w|·duration) plus the presliding distance.
    Tolerances: x against the presliding distance (1/s; LuGre's Fs/σ0), ẋ against it
    over the time the friction needs to move the mass that far, ∫e so that Ki·∫e is
    known to Fs's tolerance, LuGre's bristle z against Fs/σ0.
    """
    params = dict(params)
    z_ba = params.pop("z_ba")
    if model == "lugre":
        check_fraction("z_ba", z_ba)
        q, plant = _lugre_params(params)
        steady = plant_steady(model, q)
        travel = q["Fs"] / q["sigma0"]
        y0 = np.zeros(4)
    else:
        plant = _presliding_params(z_ba=z_ba, **params)
        steady = plant_steady(model, params)
        travel = 1.0 / params["s"]
        y0 = np.zeros(3)
    m, level = plant[_L_M if model == "lugre" else _P_M], max(steady["Fc"], steady["Fs"])
    time_scale = math.sqrt(m * travel / level)
    comp_params = {**steady, **(compensation.get("params") or {})}
    scale = abs(reference.get("h") or 0.0) + abs(reference.get("w") or 0.0) * duration + travel
    block, sr = loop_block(controller, reference,
                           {"scale": compensation["scale"], "params": comp_params}, z_ba,
                           RUNAWAY_FACTOR * scale)
    atol = [travel, travel / time_scale] + ([travel] if model == "lugre" else [])
    atol.append(level / block[_KI - 9] if block[_KI - 9] > 0 else travel * time_scale)
    # virgin (x_r = 0, F_r = 0, d = +1), a stick phase from t = 0, no reversal yet
    mem0 = np.array([0.0, 0.0, 1.0, sr, 0.0, 1.0, 0.0])
    return np.concatenate([plant, block]), y0, mem0, 1e-3 * rtol * np.array(atol)
