"""The effect library of MODEL.md §7: each effect is one object.

An :class:`Effect` knows everything about itself that the fit, the diagnosis, the
report, the text and the data panel need: its name and kinds, its parameters (units,
bounds, transform), when the data can show it (:meth:`Effect.unavailable`), starting
values read off a residual (:meth:`Effect.starts`), the residual signature that points to
it (:meth:`Effect.signature`), the regressor its residual plot uses, and how it changes
the prediction (the hooks below, called by :mod:`breakaway.identify.models` in a fixed
order). Adding an effect means adding one class here.

Prediction hooks (each returns its input unchanged unless the effect overrides it):

``body_motion(pb, p, ctx)``   timeseries: the sliding body's x, v, d, engaged (play)
``slip_velocity(pb, p, v)``   the velocity g is evaluated at (frictional lag)
``levels(pb, p, Fc, Fs, neg)`` per-row (Fc, Fs): negative-direction levels, dwell
``scale_g(pb, p, g)``         the Stribeck magnitude (drift)
``target(pb, p, v)``          added to the steady target d·g (viscous σ·v)
``sensor(pb, p, F, ctx)``     what the sensor adds to the friction (offset, inertia, …)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numba import njit
from scipy.signal import lombscargle

from ..presliding import shape_scalar
from ..quasistatic import e12_acceleration, e12_velocity
from .residuals import correlation

#: The break-away kind's fixed reading of E13 (MODEL.md §6): F̂ = avg at z* = 0.95.
BREAKAWAY_Z = 0.95
#: Bounds of the Stribeck exponent in fits (δ > 0, |δ| >= 0.05).
DELTA_BOUNDS = (0.05, 10.0)
#: Share of the moving rows each direction needs before direction effects are tried.
MIN_DIRECTION_SHARE = 0.05
#: ... and at least this many rows.
MIN_ROWS_PER_DIRECTION = 5
#: Distinct rates break-away data need before rate effects (and the Stribeck shape) are
#: determined (MODEL.md §8 ``single-rate``).
MIN_RATES = 3
#: The travel must hold this many wavelengths of a ripple.
MIN_RIPPLE_PERIODS = 2.0


@dataclass(frozen=True)
class Param:
    """One fitted parameter.

    Attributes
    ----------
    name : str
        The report's key.
    unit : str
        SI unit for linear motion (N, m); :func:`unit_of` turns it rotary.
    bounds : callable
        ``bounds(scales) -> (lo, hi)`` in the parameter's own units.
    log : bool
        Carried as its logarithm in the fit (scale parameters over decades).
    gap_of : str or None
        Carried as ``value − params[gap_of] >= 0`` (``Fs`` above ``Fc``).
    profiled : bool
        Switches the model discretely: profiled on a grid, not moved by the Jacobian.
    relative : bool
        Its relative standard error means something (not for an angle).
    """

    name: str
    unit: str
    bounds: Callable
    log: bool = False
    gap_of: str | None = None
    profiled: bool = False
    relative: bool = True


def _level(sc):
    return 1e-9 * sc.force, 20 * sc.force


BASE_PARAMS: dict[str, Param] = {p.name: p for p in (
    Param("Fc", "N", _level),
    Param("Fs", "N", lambda sc: (0.0, 20 * sc.force), gap_of="Fc"),
    # a Stribeck velocity far below every measured speed is not identifiable and is a
    # degenerate basin (g = Fc at any speed but exactly 0)
    Param("V", "m/s", lambda sc: (1e-3 * sc.speed, 1e4 * sc.speed), log=True),
    Param("delta", "", lambda sc: DELTA_BOUNDS),
    Param("s", "1/m", lambda sc: (1e-2 / sc.travel, max(1e3 / sc.step, 1e2 / sc.travel)),
          log=True),
)}

_ROTARY = {"N·s/m": "N·m·s/rad", "m/s": "rad/s", "1/m": "1/rad", "kg": "kg·m²", "N": "N·m",
           "m": "rad", "m/s²": "rad/s²", "N/s": "N·m/s"}


def unit_of(unit: str, rotary: bool) -> str:
    """The unit of a quantity for linear or rotary data (N → N·m, m → rad, …)."""
    return _ROTARY.get(unit, unit) if rotary else unit


# ---------------------------------------------------------------------------------
# small helpers shared by the effects
# ---------------------------------------------------------------------------------


def _project(r, basis) -> float:
    """Least-squares coefficient of ``r`` on one basis vector."""
    return float(np.dot(r, basis) / max(float(np.dot(basis, basis)), 1e-300))


def _fmt(value) -> str:
    return f"{value:.3g}"


# ---------------------------------------------------------------------------------
# the effect base class
# ---------------------------------------------------------------------------------


class Effect:
    """One effect the base model lacks (MODEL.md §7); subclasses fill in the hooks."""

    name: str = ""
    kinds: tuple[str, ...] = ()
    params: tuple[Param, ...] = ()
    description: str = ""
    #: x-axis of the residual plot that shows the effect, per kind
    regressor: dict[str, str] = {}

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.params)

    def unavailable(self, pb) -> str | None:
        """Why the data cannot show this effect (None: it can be tried)."""
        return None

    def refuse(self, pb, residual) -> str | None:
        """Why the current residual rules the effect out this round (None: try it)."""
        return None

    def starts(self, pb, current: dict, residual) -> list[dict]:
        """Starting values of the effect's parameters, read off the current residual."""
        raise NotImplementedError

    def signature(self, pb, residual, params: dict) -> str:
        """One sentence on what in the residual points to this effect."""
        raise NotImplementedError

    # prediction hooks: neutral by default
    def body_motion(self, pb, p, ctx):
        return ctx

    def slip_velocity(self, pb, p, v):
        return v

    def levels(self, pb, p, Fc, Fs, negative):
        return Fc, Fs

    def scale_g(self, pb, p, g):
        return g

    def target(self, pb, p, v):
        return 0.0

    def sensor(self, pb, p, F, ctx):
        return F


def _needs_both_directions(pb) -> str | None:
    counts = pb.direction_counts()
    if counts is None:
        return "the file has no direction column"
    pos, neg, total = counts
    need = max(MIN_ROWS_PER_DIRECTION, math.ceil(MIN_DIRECTION_SHARE * total))
    if min(pos, neg) < need:
        return (f"one-direction: {pos} rows move positive and {neg} negative; each "
                f"direction needs at least {need} to separate levels or an offset")
    return None


def _needs_rates(pb) -> str | None:
    if pb.kind == "breakaway" and pb.distinct_rates < MIN_RATES:
        return (f"single-rate: {pb.distinct_rates} distinct rate(s); a rate effect needs "
                f"at least {MIN_RATES}")
    return None


# ---------------------------------------------------------------------------------
# the library
# ---------------------------------------------------------------------------------


class Viscous(Effect):
    name = "viscous"
    kinds = ("timeseries", "steady", "breakaway")
    params = (Param("sigma", "N·s/m", lambda sc: (0.0, 100 * sc.force / sc.speed)),)
    description = "viscous friction σ·v added to the steady state"
    regressor = {"timeseries": "v", "steady": "v", "breakaway": "k"}

    def unavailable(self, pb):
        return _needs_rates(pb)

    def target(self, pb, p, v):
        return p["sigma"] * v

    def starts(self, pb, current, r):
        v = pb.speed_at_breakaway(current) if pb.kind == "breakaway" else pb.v
        return [{"sigma": max(_project(r, v), 0.0)}]

    def signature(self, pb, r, params):
        sliding, v, d = pb.sliding_rows(), pb.regressor_speed(), pb.signed_direction()
        c = correlation(r[sliding] * d[sliding], np.abs(v[sliding]))
        what = "k" if pb.kind == "breakaway" else "|v| in sliding"
        return f"the residual grows with {what} in the direction of motion (r = {c:.2f})"


class Asymmetry(Effect):
    name = "asymmetry"
    kinds = ("timeseries", "steady", "breakaway")
    params = (Param("Fc_neg", "N", _level),
              Param("Fs_neg", "N", lambda sc: (0.0, 20 * sc.force), gap_of="Fc_neg"))
    description = "separate Coulomb and Stribeck levels in the negative direction"
    regressor = {"timeseries": "v", "steady": "v", "breakaway": "direction"}

    def unavailable(self, pb):
        return _needs_both_directions(pb)

    def levels(self, pb, p, Fc, Fs, negative):
        return (np.where(negative, p["Fc_neg"], Fc), np.where(negative, p["Fs_neg"], Fs))

    def starts(self, pb, current, r):
        negative = pb.negative_rows
        sel = negative & pb.sliding_rows()
        # measured |F| minus the model's, moving negative (breakaway F_ba is a magnitude)
        sign = 1.0 if pb.kind == "breakaway" else -1.0
        shift = sign * float(np.median(r[sel])) if np.any(sel) else 0.0
        Fc_neg = max(current["Fc"] + shift, 1e-3 * current["Fc"])
        Fs_neg = max(current["Fs"] + shift, Fc_neg)
        return [{"Fc_neg": Fc_neg, "Fs_neg": Fs_neg},
                {"Fc_neg": current["Fc"], "Fs_neg": current["Fs"]}]

    def signature(self, pb, r, params):
        mp, mn = _direction_means(pb, r)
        if pb.kind == "breakaway":
            return (f"the break-away force differs by direction: residual {_fmt(mp)} N for "
                    f"direction +1 and {_fmt(mn)} N for direction -1")
        return (f"the sliding levels differ by direction: measured |F| minus the model's "
                f"is {mp:+.3g} N moving positive and {-mn:+.3g} N moving negative")


def _direction_means(pb, r):
    sliding, d = pb.sliding_rows(), pb.signed_direction()
    pos, neg = r[sliding & (d > 0)], r[sliding & (d < 0)]
    return (float(np.mean(pos)) if pos.size else 0.0, float(np.mean(neg)) if neg.size else 0.0)


class Offset(Effect):
    name = "offset"
    kinds = ("timeseries", "steady")
    params = (Param("F_offset", "N", lambda sc: (-10 * sc.force, 10 * sc.force)),)
    description = "a constant bias of the force sensor"
    regressor = {"timeseries": "t", "steady": "v"}

    def unavailable(self, pb):
        return _needs_both_directions(pb)

    def sensor(self, pb, p, F, ctx):
        return F + p["F_offset"]

    def starts(self, pb, current, r):
        return [{"F_offset": float(np.median(r))}]

    def signature(self, pb, r, params):
        mp, mn = _direction_means(pb, r)
        return (f"the residual has the same sign in both directions: mean {_fmt(mp)} N "
                f"moving positive, {_fmt(mn)} N moving negative")


class Drift(Effect):
    name = "drift"
    kinds = ("timeseries",)
    params = (Param("alpha", "1/s", lambda sc: (-0.95 / sc.duration, 20.0 / sc.duration)),)
    description = "friction level drifting linearly in time (wear, temperature)"
    regressor = {"timeseries": "t"}

    def scale_g(self, pb, p, g):
        return g * (1.0 + p["alpha"] * (pb.t - pb.t[0]))

    def starts(self, pb, current, r):
        basis = (pb.t - pb.t[0]) * (pb.measured - r)
        lo, hi = self.params[0].bounds(pb.scales)
        return [{"alpha": float(np.clip(_project(r, basis), 0.9 * lo, 0.9 * hi))}]

    def signature(self, pb, r, params):
        sliding, d = pb.sliding_rows(), pb.signed_direction()
        c = correlation(r[sliding] * d[sliding], pb.t[sliding])
        return f"the sliding-level error changes steadily with time (r = {c:.2f} against t)"


class Inertia(Effect):
    name = "inertia"
    kinds = ("timeseries", "breakaway")
    params = (Param("m_e", "kg", lambda sc: (0.0, 100 * sc.force / sc.accel)),)
    description = "an inertial force m_e·a in the measured force"
    regressor = {"timeseries": "a", "breakaway": "k"}

    def unavailable(self, pb):
        return _needs_rates(pb)

    def _acceleration(self, pb, F_hat):
        if pb.kind == "breakaway":
            return e12_acceleration(pb.k, F_hat, pb.s, BREAKAWAY_Z)
        return pb.a

    def sensor(self, pb, p, F, ctx):
        return F + p["m_e"] * self._acceleration(pb, ctx.get("F_hat"))

    def starts(self, pb, current, r):
        F_hat = current["Fc"] + (current["Fs"] - current["Fc"]) / 2
        return [{"m_e": max(_project(r, self._acceleration(pb, F_hat)), 0.0)}]

    def signature(self, pb, r, params):
        if pb.kind == "breakaway":
            c = correlation(r, pb.k**2)
            return f"the residual grows with k² like an inertial term (r = {c:.2f})"
        return f"the residual follows the acceleration a = dv/dt (r = {correlation(r, pb.a):.2f})"


class Ripple(Effect):
    name = "ripple"
    kinds = ("timeseries",)
    params = (Param("A", "N", lambda sc: (0.0, 10 * sc.force)),
              # the travel must hold two wavelengths (MODEL.md §8 short-travel)
              Param("wavelength", "m",
                    lambda sc: (2 * sc.step, sc.travel / MIN_RIPPLE_PERIODS), log=True),
              Param("phase", "rad", lambda sc: (-4 * math.pi, 4 * math.pi), relative=False))
    description = "position-dependent friction A·sin(2πx/λ + φ)"
    regressor = {"timeseries": "x"}

    def unavailable(self, pb):
        if pb.scales.travel < 8 * MIN_RIPPLE_PERIODS * pb.scales.step:
            return "short-travel: the travel holds too few position steps for a ripple"
        return None

    def sensor(self, pb, p, F, ctx):
        return F + p["A"] * np.sin(2 * np.pi * pb.x / p["wavelength"] + p["phase"])

    def refuse(self, pb, residual):
        lam = long_wavelength(pb, residual)
        if lam is None:
            return None
        return (f"short-travel: the residual's dependence on x is strongest at a wavelength "
                f"of about {lam:.3g}, but the travel ({pb.scales.travel:.3g}) holds fewer "
                f"than {MIN_RIPPLE_PERIODS:g} such periods")

    def starts(self, pb, current, r):
        """Wavelengths of the strongest periodogram peaks of the residual against x."""
        x = pb.x
        travel, step = pb.scales.travel, pb.scales.step
        top = travel / MIN_RIPPLE_PERIODS
        wavelengths = np.geomspace(min(max(4 * step, travel / 2000), top / 2), top, 600)
        power = periodogram(x, r, wavelengths)
        starts = []
        for idx in np.argsort(power)[::-1][:40]:
            lam = wavelengths[idx]
            if any(abs(math.log(lam / s["wavelength"])) < 0.05 for s in starts):
                continue
            phase = 2 * np.pi * x / lam
            basis = np.column_stack([np.sin(phase), np.cos(phase)])
            (c_sin, c_cos), *_ = np.linalg.lstsq(basis, r, rcond=None)
            starts.append({"A": float(math.hypot(c_sin, c_cos)), "wavelength": float(lam),
                           "phase": float(math.atan2(c_cos, c_sin))})
            if len(starts) == 3:
                break
        return starts

    def signature(self, pb, r, params):
        lam = params.get("wavelength")
        if lam is None:
            return "the residual is periodic in x"
        phase = 2 * np.pi * pb.x / lam
        c = math.hypot(correlation(r, np.sin(phase)), correlation(r, np.cos(phase)))
        return (f"the residual is periodic in x with wavelength {_fmt(lam)} m "
                f"(correlation {c:.2f} with a sinusoid of x)")


def long_wavelength(pb, r):
    """The wavelength at which ``r`` depends most on x when that is too long for the
    travel to hold two periods (else None)."""
    travel, step = pb.scales.travel, pb.scales.step
    short = np.geomspace(max(4 * step, travel / 2000), travel / MIN_RIPPLE_PERIODS, 200)
    long = np.geomspace(travel / MIN_RIPPLE_PERIODS, 4 * travel, 60)
    p_long = periodogram(pb.x, r, long)
    if p_long.max() <= periodogram(pb.x, r, short).max():
        return None
    return float(long[int(np.argmax(p_long))])


def periodogram(x, r, wavelengths):
    """Lomb–Scargle power of ``r`` against ``x`` at ``wavelengths`` (long records are
    subsampled: the cost is rows × wavelengths)."""
    stride = max(1, x.size // 4000)
    return lombscargle(x[::stride], r[::stride] - r.mean(), 2 * np.pi / wavelengths)


@njit(cache=True)
def lag_filter(v, t, tau):
    """First-order lag of v: ``v_f,i = v_f,i−1 + (1 − exp(−Δt_i/τ))·(v_i − v_f,i−1)``."""
    n = v.size
    out = np.empty(n)
    out[0] = v[0]
    for i in range(1, n):
        w = 1.0 - math.exp(-(t[i] - t[i - 1]) / tau) if tau > 0.0 else 1.0
        out[i] = out[i - 1] + w * (v[i] - out[i - 1])
    return out


class Lag(Effect):
    name = "lag"
    kinds = ("timeseries",)
    params = (Param("tau", "s", lambda sc: (0.0, sc.duration / 4)),)
    description = "frictional lag: the Stribeck level follows a filtered velocity"
    regressor = {"timeseries": "v"}

    def slip_velocity(self, pb, p, v):
        return lag_filter(v, pb.t, p["tau"])

    def starts(self, pb, current, r):
        char_time = pb.scales.speed / pb.scales.accel
        return [{"tau": float(tau)} for tau in char_time * np.array([0.003, 0.01, 0.03, 0.1, 0.3])]

    def signature(self, pb, r, params):
        sliding, d = pb.sliding_rows(), pb.signed_direction()
        c = correlation(r[sliding] * d[sliding], pb.a[sliding] * d[sliding])
        return (f"in sliding the error depends on whether the speed rises or falls "
                f"(r = {c:.2f} against the acceleration along the motion): F–v loops open")


@njit(cache=True)
def play_operator(x, play):
    """Body position behind a play of width ``play`` (MODEL.md §7 ``backlash``).

    ``x_c,i = min(max(x_c,i−1, x_i − b/2), x_i + b/2)``, ``x_c,0 = x_0``. Returns the
    body position and whether the body is engaged (at the edge of the play).
    """
    n = x.size
    xc = np.empty(n)
    engaged = np.zeros(n, dtype=np.bool_)
    half = 0.5 * play
    xc[0] = x[0]
    engaged[0] = play == 0.0
    for i in range(1, n):
        lo = x[i] - half
        hi = x[i] + half
        c = xc[i - 1]
        if c <= lo:
            xc[i] = lo
            engaged[i] = True
        elif c >= hi:
            xc[i] = hi
            engaged[i] = True
        else:
            xc[i] = c
            engaged[i] = play == 0.0
    return xc, engaged


@njit(cache=True)
def engaged_presliding(xc, d, target, s, F_r0, engaged):
    """(E6') on the body position with the play's re-engagements (MODEL.md §7).

    Each re-engagement starts a branch with ``x_r = x_c,i−1`` and ``F_r = 0``; the
    measured force is the friction while engaged and 0 while free.
    """
    n = xc.size
    friction = np.empty(n)
    out = np.empty(n)
    x_r = xc[0]
    F_r = F_r0
    for i in range(n):
        if i > 0:
            if engaged[i] and not engaged[i - 1]:
                x_r = xc[i - 1]
                F_r = 0.0
            elif d[i] != d[i - 1]:
                x_r = xc[i - 1]
                F_r = friction[i - 1]
        friction[i] = F_r + (target[i] - F_r) * shape_scalar(s * abs(xc[i] - x_r))
        out[i] = friction[i] if engaged[i] else 0.0
    return out


class Backlash(Effect):
    name = "backlash"
    kinds = ("timeseries",)
    params = (Param("play", "m", lambda sc: (0.0, sc.travel / 2), profiled=True),)
    description = "a play of width b between the measured point and the sliding body"
    regressor = {"timeseries": "x"}

    def unavailable(self, pb):
        if pb.reversals < 2:
            return f"the record has {pb.reversals} reversal(s); a play shows at reversals"
        return None

    def body_motion(self, pb, p, ctx):
        if p["play"] <= 0:
            return ctx
        xc, engaged = play_operator(ctx["x"], p["play"])
        return {**ctx, "x": xc, "v": pb.kinematic_velocity(xc), "d": pb.kinematic_direction(xc),
                "engaged": engaged}

    def starts(self, pb, current, r):
        travel = pb.scales.travel
        presliding = 1.0 / current["s"]
        plays = np.concatenate([travel * np.array([0.003, 0.01, 0.03, 0.1]),
                                presliding * np.array([0.3, 1.0, 3.0])])
        plays = plays[plays < travel / 2]
        return [{"play": float(b)} for b in plays]

    def signature(self, pb, r, params):
        after = pb.after_reversal(max(2.0 / params.get("s", math.inf), params.get("play", 0.0) * 1.5))
        if after.any() and (~after).any():
            inside = math.sqrt(float(np.mean(r[after] ** 2)))
            outside = math.sqrt(float(np.mean(r[~after] ** 2)))
            return (f"the residual concentrates right after reversals: RMS {_fmt(inside)} N "
                    f"in the first part of each new stroke against {_fmt(outside)} N elsewhere")
        return "the residual concentrates right after reversals"


class Dwell(Effect):
    name = "dwell"
    kinds = ("breakaway",)
    params = (Param("zeta", "", lambda sc: (0.0, 100.0)),
              Param("tau_d", "s", lambda sc: (1e-4 * max(sc.dwell, 1e-6), 1e3 * max(sc.dwell, 1e-6)),
                    log=True))
    description = "stiction rising with the dwell time before the ramp"
    regressor = {"breakaway": "dwell"}

    def unavailable(self, pb):
        if "dwell" not in pb.data.columns:
            return "the file has no dwell column"
        distinct = np.unique(pb.dwell).size
        if distinct < 2:
            return "every row has the same dwell time, which only rescales Fs"
        if pb.level_only:
            return "single-rate: the Stribeck gap Fs − Fc that dwell scales is not determined"
        return None

    def levels(self, pb, p, Fc, Fs, negative):
        return Fc, Fc + (Fs - Fc) * (1.0 + p["zeta"] * np.log1p(pb.dwell / p["tau_d"]))

    def starts(self, pb, current, r):
        positive = pb.dwell[pb.dwell > 0]
        scale = float(np.median(positive)) if positive.size else 1.0
        return [{"zeta": z, "tau_d": scale * f} for z in (0.1, 0.5) for f in (0.1, 1.0, 10.0)]

    def signature(self, pb, r, params):
        c = correlation(r, np.log1p(pb.dwell))
        return f"the break-away force rises with the dwell time (r = {c:.2f} against ln(1 + dwell))"


class Detection(Effect):
    name = "detection"
    kinds = ("breakaway",)
    params = (Param("tau_det", "s", lambda sc: (0.0, 100 * sc.force / sc.rate)),)
    description = "the rig notices motion a time τ_det late while the force keeps ramping"
    regressor = {"breakaway": "k"}

    def unavailable(self, pb):
        return _needs_rates(pb)

    def sensor(self, pb, p, F, ctx):
        return F + pb.k * p["tau_det"]

    def starts(self, pb, current, r):
        return [{"tau_det": max(_project(r, pb.k), 0.0)}]

    def signature(self, pb, r, params):
        return (f"the break-away force rises linearly with the rate k, against E13's fall "
                f"(r = {correlation(r, pb.k):.2f})")


def viscous_equivalent_of_detection(tau_det, s, F_hat):
    """σ that raises F_ba like a detection delay τ_det (MODEL.md §7):
    ``σ·ẋ* = k·τ_det`` with ``ẋ* = k/(s·F̂·|ln z*|)`` gives ``σ = τ_det·s·F̂·|ln z*|``."""
    return tau_det / float(e12_velocity(1.0, F_hat, s, BREAKAWAY_Z))


EFFECTS: dict[str, Effect] = {e.name: e for e in (
    Viscous(), Asymmetry(), Offset(), Drift(), Inertia(), Ripple(), Lag(), Backlash(),
    Dwell(), Detection())}


def effects_for(kind: str) -> list[Effect]:
    """The library's effects that apply to ``kind``, in library order."""
    return [e for e in EFFECTS.values() if kind in e.kinds]


def availability(problem) -> dict[str, str | None]:
    """Each effect of the problem's kind: None when the data can show it, else why not."""
    return {e.name: e.unavailable(problem) for e in effects_for(problem.kind)}


def param_spec(name: str) -> Param:
    """The :class:`Param` of a base or effect parameter."""
    if name in BASE_PARAMS:
        return BASE_PARAMS[name]
    for effect in EFFECTS.values():
        for p in effect.params:
            if p.name == name:
                return p
    raise KeyError(name)


__all__ = ["availability", "BASE_PARAMS", "BREAKAWAY_Z", "DELTA_BOUNDS", "EFFECTS", "Effect", "Param",
           "effects_for", "engaged_presliding", "lag_filter", "long_wavelength", "param_spec", "periodogram",
           "play_operator", "unit_of", "viscous_equivalent_of_detection"]
