"""Forward models of the three data kinds with any set of §7 effects, and their
parameter layout for fitting (MODEL.md §6, §7).

A :class:`Problem` binds a dataset to a set of effects. It maps between the report's
parameter dictionary (``Fc``, ``Fs``, ``V``, ``delta``, ``s`` and the §7 keys) and the
vector θ that ``scipy.optimize.least_squares`` moves, with bounds from §1: ``Fs`` is
carried as ``Fs − Fc >= 0``, ``V``, ``s``, ``wavelength`` and ``tau_d`` as logarithms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..presliding import _presliding_kernel, motion_direction, shape_scalar
from .csvdata import Dataset

BASE_PARAMS = {
    "timeseries": ("Fc", "Fs", "V", "delta", "s"),
    "steady": ("Fc", "Fs", "V", "delta"),
    "breakaway": ("Fc", "Fs", "V", "delta"),
}
#: The break-away kind's fixed reading of E13 (MODEL.md §6).
BREAKAWAY_Z = 0.95
#: Bounds of the Stribeck exponent in fits (δ > 0, |δ| >= 0.05).
DELTA_BOUNDS = (0.05, 10.0)

# ---------------------------------------------------------------------------------
# compiled kernels: the play operator, the frictional-lag filter, E6' with re-engagement
# ---------------------------------------------------------------------------------


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
def lag_filter(v, t, tau):
    """First-order lag of v: ``v_f,i = v_f,i−1 + (1 − exp(−Δt_i/τ))·(v_i − v_f,i−1)``."""
    n = v.size
    out = np.empty(n)
    out[0] = v[0]
    for i in range(1, n):
        if tau > 0.0:
            w = 1.0 - math.exp(-(t[i] - t[i - 1]) / tau)
        else:
            w = 1.0
        out[i] = out[i - 1] + w * (v[i] - out[i - 1])
    return out


@njit(cache=True)
def _engaged_kernel(xc, d, target, s, F_r0, engaged):
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
        z = s * abs(xc[i] - x_r)
        shape = shape_scalar(z)
        friction[i] = F_r + (target[i] - F_r) * shape
        out[i] = friction[i] if engaged[i] else 0.0
    return out


def _stribeck(speed, Fc, Fs, V, delta):
    with np.errstate(over="ignore", divide="ignore"):
        return Fc + (Fs - Fc) * np.exp(-np.power(np.abs(speed) / V, delta))


# ---------------------------------------------------------------------------------
# parameter layout
# ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Scales:
    """Typical magnitudes of a dataset, used for bounds and initial guesses."""

    force: float  # [N]
    speed: float  # [m/s]
    travel: float  # peak-to-peak x [m] (timeseries)
    duration: float  # [s] (timeseries)
    accel: float  # [m/s²] (timeseries)
    step: float  # median |Δx| [m] (timeseries)
    dwell: float  # largest dwell [s] (breakaway)


@dataclass
class Problem:
    """A dataset bound to a set of effects: prediction and the θ ↔ params map.

    Parameters
    ----------
    data : Dataset
        Parsed measurement (:mod:`breakaway.identify.csvdata`).
    effects : tuple of str
        Names from :data:`breakaway.identify.effects.EFFECTS`.
    fixed : dict, optional
        Parameters held at the given values (left out of θ), e.g. a profiled play.
    """

    data: Dataset
    effects: tuple[str, ...] = ()
    fixed: dict = field(default_factory=dict)
    names: tuple[str, ...] = field(init=False)
    measured: np.ndarray = field(init=False)
    scales: Scales = field(init=False)

    def __post_init__(self):
        from .effects import EFFECTS

        kind = self.data.kind
        names = list(BASE_PARAMS[kind])
        for effect in self.effects:
            names.extend(EFFECTS[effect].params)
        unknown = set(self.fixed) - set(names)
        if unknown:
            raise ValueError(f"cannot fix {sorted(unknown)}: not parameters of this model")
        self.names = tuple(n for n in names if n not in self.fixed)
        cols = self.data.columns
        if kind == "timeseries":
            self.t, self.x = cols["t"], cols["x"]
            self.measured = cols["F"]
            self.v = np.gradient(self.x, self.t)
            self.a = np.gradient(self.v, self.t)
            self.d = motion_direction(self.x)
            self.F0 = self.data.meta_float("f0", 0.0)
            steps = np.abs(np.diff(self.x))
            moving = steps[steps > 0]
            self.scales = Scales(
                force=_robust_scale(self.measured),
                speed=_robust_scale(self.v),
                travel=float(np.ptp(self.x)) or 1.0,
                duration=float(self.t[-1] - self.t[0]),
                accel=_robust_scale(self.a),
                step=float(np.median(moving)) if moving.size else 1.0,
                dwell=0.0,
            )
        elif kind == "steady":
            self.v = cols["v"]
            self.measured = cols["F"]
            self.scales = Scales(_robust_scale(self.measured), _robust_scale(self.v),
                                 *_NO_MOTION)
        else:
            self.k = cols["k"]
            self.measured = cols["F_ba"]
            self.s = self.data.meta_float("s", 1.0)
            if not self.s > 0:
                raise ValueError(f"metadata s must be > 0, got {self.s}")
            self.direction = cols.get("direction", np.ones_like(self.k))
            self.dwell = cols.get("dwell", np.zeros_like(self.k))
            force = _robust_scale(self.measured)
            speed = float(np.max(self.k)) / (self.s * force * -math.log(BREAKAWAY_Z))
            self.scales = Scales(force, speed, *_NO_MOTION[:4],
                                 float(np.max(self.dwell)) if self.dwell.size else 0.0)

    # -- θ ↔ params ----------------------------------------------------------------
    def to_theta(self, params: dict) -> np.ndarray:
        theta = []
        for name in self.names:
            value = params[name]
            if name == "Fs":
                value = params["Fs"] - params["Fc"]
            elif name == "Fs_neg":
                value = params["Fs_neg"] - params["Fc_neg"]
            elif name in LOG_PARAMS:
                value = math.log(value)
            theta.append(value)
        return np.clip(np.array(theta, dtype=float), *self.bounds())

    def to_params(self, theta) -> dict:
        p = {}
        for name, value in zip(self.names, np.asarray(theta, dtype=float)):
            p[name] = math.exp(value) if name in LOG_PARAMS else float(value)
        if "Fs" in p:
            p["Fs"] += p["Fc"]
        if "Fs_neg" in p:
            p["Fs_neg"] += p["Fc_neg"]
        p.update(self.fixed)
        return p

    def bounds(self):
        sc = self.scales
        F, v = sc.force, sc.speed
        table = {
            "Fc": (1e-9 * F, 20 * F),
            "Fs": (0.0, 20 * F),
            # a Stribeck velocity far below every measured speed is not identifiable and
            # is a degenerate basin (g = Fc at any speed but exactly 0)
            "V": (math.log(1e-3 * v), math.log(1e4 * v)),
            "delta": DELTA_BOUNDS,
            "s": (math.log(1e-2 / sc.travel), math.log(max(1e3 / sc.step, 1e2 / sc.travel))),
            "sigma": (0.0, 100 * F / v),
            "Fc_neg": (1e-9 * F, 20 * F),
            "Fs_neg": (0.0, 20 * F),
            "F_offset": (-10 * F, 10 * F),
            "alpha": (-0.95 / max(sc.duration, 1e-12), 20.0 / max(sc.duration, 1e-12)),
            "m_e": (0.0, 100 * F / max(sc.accel, 1e-12)),
            "A": (0.0, 10 * F),
            "wavelength": (math.log(2 * sc.step), math.log(2 * sc.travel)),
            "phase": (-4 * math.pi, 4 * math.pi),
            "tau": (0.0, max(sc.duration, 1e-12) / 4),
            "play": (0.0, sc.travel / 2),
            "zeta": (0.0, 100.0),
            "tau_d": (math.log(1e-4 * max(sc.dwell, 1e-6)), math.log(1e3 * max(sc.dwell, 1e-6))),
        }
        lo = np.array([table[n][0] for n in self.names], dtype=float)
        hi = np.array([table[n][1] for n in self.names], dtype=float)
        return lo, hi

    # -- prediction ---------------------------------------------------------------
    def predict(self, params: dict) -> np.ndarray:
        """Predicted measured force for every row [N]."""
        kind = self.data.kind
        if kind == "timeseries":
            return self._predict_timeseries(params)
        if kind == "steady":
            return self._predict_steady(params)
        return self._predict_breakaway(params)

    def _levels(self, params, negative):
        """Per-row (Fc, Fs): the negative-direction levels where ``negative`` (asymmetry)."""
        Fc, Fs = params["Fc"], params["Fs"]
        if "asymmetry" in self.effects:
            Fc = np.where(negative, params["Fc_neg"], Fc)
            Fs = np.where(negative, params["Fs_neg"], Fs)
        return Fc, Fs

    def _predict_timeseries(self, p):
        effects = self.effects
        if "backlash" in effects and p["play"] > 0:
            xc, engaged = play_operator(self.x, p["play"])
            v = np.gradient(xc, self.t)
            d = motion_direction(xc)
        else:
            xc, engaged, v, d = self.x, None, self.v, self.d
        v_slip = lag_filter(v, self.t, p["tau"]) if "lag" in effects else v
        Fc, Fs = self._levels(p, d < 0)
        g = _stribeck(v_slip, Fc, Fs, p["V"], p["delta"])
        if "drift" in effects:
            g = g * (1.0 + p["alpha"] * (self.t - self.t[0]))
        target = d * g
        if "viscous" in effects:
            target = target + p["sigma"] * v
        if engaged is None:
            F = _presliding_kernel(xc, d, target, p["s"], self.F0)
        else:
            F = _engaged_kernel(xc, d, target, p["s"], self.F0, engaged)
        if "offset" in effects:
            F = F + p["F_offset"]
        if "inertia" in effects:
            F = F + p["m_e"] * self.a
        if "ripple" in effects:
            F = F + p["A"] * np.sin(2 * np.pi * self.x / p["wavelength"] + p["phase"])
        return F

    def _predict_steady(self, p):
        Fc, Fs = self._levels(p, self.v < 0)
        F = np.sign(self.v) * _stribeck(self.v, Fc, Fs, p["V"], p["delta"])
        if "viscous" in self.effects:
            F = F + p["sigma"] * self.v
        if "offset" in self.effects:
            F = F + p["F_offset"]
        return F

    def _predict_breakaway(self, p):
        Fc, Fs = self._levels(p, self.direction < 0)
        if "dwell" in self.effects:
            Fs = Fc + (Fs - Fc) * (1.0 + p["zeta"] * np.log1p(self.dwell / p["tau_d"]))
        F_hat = Fc + (Fs - Fc) / 2  # the 'avg' reading of E13
        log_z = -math.log(BREAKAWAY_Z)
        speed = self.k / (self.s * F_hat * log_z)  # E12 at z*
        F = _stribeck(speed, Fc, Fs, p["V"], p["delta"])
        if "viscous" in self.effects:
            F = F + p["sigma"] * speed
        if "inertia" in self.effects:
            F = F + p["m_e"] * self.k**2 / (self.s * F_hat**2 * BREAKAWAY_Z * log_z**3)
        return F


#: travel, duration, accel, step, dwell of kinds without a motion record (unused there,
#: but finite so every bound is defined)
_NO_MOTION = (1.0, 1.0, 1.0, 1.0, 0.0)
#: Parameters that θ carries as logarithms.
LOG_PARAMS = frozenset({"V", "s", "wavelength", "tau_d"})


def _robust_scale(values) -> float:
    """A typical magnitude: the 95th percentile of |values| (1 if that is 0)."""
    scale = float(np.percentile(np.abs(values), 95))
    return scale if scale > 0 else 1.0
