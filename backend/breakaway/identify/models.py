"""Forward models of the three data kinds with any set of §7 effects (MODEL.md §6, §7).

One :class:`Problem` subclass per kind binds a dataset to a set of effects. The base
class maps between the report's parameter dictionary and the vector θ that
``scipy.optimize.least_squares`` moves (bounds and transforms from each parameter's
:class:`~breakaway.identify.effects.Param`); each kind's ``predict`` runs the model
core's equations — g of (E2) (:func:`breakaway.steady.stribeck_kernel`), (E6')
(:func:`breakaway.presliding._presliding_kernel`), (E12) — and calls each effect's hooks
in a fixed order. :func:`problem_for` picks the class for a dataset.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass

import numpy as np

from scipy.ndimage import uniform_filter1d

from ..presliding import _presliding_kernel
from ..quasistatic import e12_acceleration, e12_velocity
from ..steady import stribeck_kernel
from .csvdata import Dataset
from .effects import BREAKAWAY_Z, EFFECTS, MIN_RATES, engaged_presliding, param_spec
from .kinematics import REVERSAL_STEPS, direction, position_noise, quantum, velocity


#: Kinematics per dataset (a fit builds many problems on one record).
_KINEMATICS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: Samples averaged before the direction of a noisy x is read.
NOISY_X_WINDOW = 21


@dataclass(frozen=True)
class Scales:
    """Typical magnitudes of a dataset, used for bounds and starting values."""

    force: float  # [N]
    speed: float  # [m/s]
    travel: float = 1.0  # peak-to-peak x [m] (timeseries)
    duration: float = 1.0  # [s] (timeseries)
    accel: float = 1.0  # [m/s²]
    step: float = 1.0  # median |Δx| while moving [m] (timeseries)
    dwell: float = 0.0  # largest dwell [s] (breakaway)
    rate: float = 1.0  # largest k [N/s] (breakaway)


def _robust_scale(values) -> float:
    """A typical magnitude: the 95th percentile of |values| (1 if that is 0)."""
    scale = float(np.percentile(np.abs(values), 95))
    return scale if scale > 0 else 1.0


class Problem:
    """A dataset bound to a set of effects: prediction and the θ ↔ params map.

    Parameters
    ----------
    data : Dataset
        Parsed measurement (:mod:`breakaway.identify.csvdata`).
    effects : sequence of str
        Names from :data:`breakaway.identify.effects.EFFECTS`.
    fixed : dict, optional
        Parameters held at the given values (left out of θ), e.g. a profiled play.
    """

    kind: str = ""
    base_names: tuple[str, ...] = ()
    #: only the level is determined: Fc is tied to Fs (and Fc_neg to Fs_neg)
    level_only: bool = False

    def __init__(self, data: Dataset, effects=(), fixed=None):
        self.data = data
        unknown = [e for e in effects if e not in EFFECTS]
        if unknown:
            raise KeyError(f"unknown effect {unknown[0]!r}: expected one of {', '.join(EFFECTS)}")
        #: in the order they were added; the hooks run in library order
        self.effects = tuple(effects)
        order = list(EFFECTS)
        self.effect_objects = [EFFECTS[e] for e in sorted(effects, key=order.index)]
        self.fixed = dict(fixed or {})
        names = list(self.base_names)
        for effect in self.effect_objects:
            names.extend(effect.keys)
        self.all_names = tuple(names)
        unknown = set(self.fixed) - set(names)
        if unknown:
            raise ValueError(f"cannot fix {sorted(unknown)}: not parameters of this model")
        self.tied = {"Fc": "Fs", "Fc_neg": "Fs_neg"} if self.level_only else {}
        self.names = tuple(n for n in names if n not in self.fixed and n not in self.tied)

    # -- θ ↔ params ----------------------------------------------------------------
    def _gap_base(self, name):
        base = param_spec(name).gap_of
        return base if base in self.names else None

    def to_theta(self, params: dict) -> np.ndarray:
        theta = []
        for name in self.names:
            value = params[name]
            spec = param_spec(name)
            gap = self._gap_base(name)
            if gap:
                value = params[name] - params[gap]
            elif spec.log:
                value = math.log(value)
            theta.append(value)
        return np.clip(np.array(theta, dtype=float), *self.bounds())

    def to_params(self, theta) -> dict:
        p = {}
        for name, value in zip(self.names, np.asarray(theta, dtype=float)):
            p[name] = math.exp(value) if param_spec(name).log else float(value)
        for name in self.names:
            gap = self._gap_base(name)
            if gap:
                p[name] += p[gap]
        for low, level in self.tied.items():
            if level in p:
                p[low] = p[level]
        p.update(self.fixed)
        return {name: p[name] for name in self.all_names}

    def bounds(self):
        lo, hi = [], []
        for name in self.names:
            spec = param_spec(name)
            if spec.gap_of and not self._gap_base(name):
                spec = param_spec(spec.gap_of)  # a tied level: bounded like the base level
            a, b = spec.bounds(self.scales)
            if spec.log:
                a, b = math.log(a), math.log(b)
            lo.append(a)
            hi.append(b)
        return np.array(lo, dtype=float), np.array(hi, dtype=float)

    def is_log(self, name) -> bool:
        return param_spec(name).log

    # -- the model ------------------------------------------------------------------
    def _levels(self, p, negative):
        Fc, Fs = p["Fc"], p["Fs"]
        for effect in self.effect_objects:
            Fc, Fs = effect.levels(self, p, Fc, Fs, negative)
        return Fc, Fs

    def predict(self, params: dict) -> np.ndarray:
        """Predicted measured force for every row [N]."""
        raise NotImplementedError

    # -- what the effects, the noise floor and the report ask of the data -------------
    def sliding_rows(self):
        return np.ones(self.data.n, dtype=bool)

    def direction_counts(self):
        """(rows moving positive, rows moving negative, rows considered), or None."""
        d = self.signed_direction()
        return int(np.count_nonzero(d > 0)), int(np.count_nonzero(d < 0)), int(d.size)

    @property
    def negative_rows(self):
        return self.signed_direction() < 0

    def variables(self) -> dict[str, np.ndarray]:
        """The regressors a residual can depend on (MODEL.md §8 ``residual_structure``)."""
        raise NotImplementedError


class TimeseriesProblem(Problem):
    """(E6') along the measured x(t) (MODEL.md §6 ``timeseries``)."""

    kind = "timeseries"
    base_names = ("Fc", "Fs", "V", "delta", "s")

    def __init__(self, data, effects=(), fixed=None):
        cols = data.columns
        self.t, self.x = cols["t"], cols["x"]
        self.measured = cols["F"]
        #: independent records (blocks of a screened series): [start, stop) pairs
        edges = [0, *data.segments, data.n]
        self.blocks = list(zip(edges[:-1], edges[1:]))
        self.F0 = data.meta_float("f0", 0.0)
        cached = _KINEMATICS.get(data)
        if cached is None:
            cached = _KINEMATICS[data] = self._kinematics()
        self.__dict__.update(cached)
        super().__init__(data, effects, fixed)

    def _kinematics(self) -> dict:
        """What every model of this record shares; computed once per dataset."""
        #: quantisation step and noise std of x (0: none), its resolution, and the
        #: reversal hysteresis: direction changes within a few resolutions are not real
        self.quantum_x = quantum(self.x)
        self.noise_x = position_noise(self.x) if self.quantum_x == 0 else 0.0
        self.resolution_x = max(self.quantum_x, self.noise_x)
        self.hysteresis = REVERSAL_STEPS * self.resolution_x
        v = self.kinematic_velocity(self.x)
        with np.errstate(divide="ignore"):
            log_speed = np.log(np.abs(v))  # g's argument, reused by every evaluation
        a = np.concatenate([np.gradient(v[i:j], self.t[i:j]) for i, j in self.blocks])
        steps = np.abs(np.diff(self.x))
        moving = steps[steps > 0]
        scales = Scales(
            force=_robust_scale(self.measured),
            speed=_robust_scale(v),
            travel=float(np.ptp(self.x)) or 1.0,
            duration=float(self.t[-1] - self.t[0]) or 1.0,
            accel=_robust_scale(a),
            step=max(float(np.median(moving)) if moving.size else 1.0, self.quantum_x),
        )
        return {"quantum_x": self.quantum_x, "noise_x": self.noise_x,
                "resolution_x": self.resolution_x, "hysteresis": self.hysteresis, "v": v,
                "log_speed": log_speed, "a": a, "d": self.kinematic_direction(self.x),
                "scales": scales}

    def kinematic_velocity(self, x):
        return np.concatenate([velocity(self.t[a:b], x[a:b], self.resolution_x)
                               for a, b in self.blocks])

    def kinematic_direction(self, x):
        if self.noise_x > 0:
            # Gaussian noise has no largest excursion: the trigger runs on x averaged
            # over 21 samples, where the noise std is 4.6× smaller than the hysteresis'
            x = uniform_filter1d(x, NOISY_X_WINDOW, mode="nearest")
        return np.concatenate([direction(x[a:b], self.hysteresis) for a, b in self.blocks])

    def _presliding(self, ctx, target, s):
        """(E6') block by block; a later block starts from its measured force."""
        out = np.empty(self.x.size)
        for a, b in self.blocks:
            F0 = self.F0 if a == 0 else float(self.measured[a])
            x, d = ctx["x"][a:b], ctx["d"][a:b]
            if ctx["engaged"] is None:
                out[a:b] = _presliding_kernel(x, d, target[a:b], s, F0)
            else:
                out[a:b] = engaged_presliding(x, d, target[a:b], s, F0, ctx["engaged"][a:b])
        return out

    @property
    def reversals(self) -> int:
        return int(np.count_nonzero(np.diff(self.d)))

    def predict(self, p, dither=None):
        """Predicted force [N]; ``dither`` [m] is added to the positions (velocities
        follow, directions stay), to propagate the resolution of x."""
        ctx = {"x": self.x, "v": self.v, "d": self.d, "engaged": None}
        if dither is not None:
            ctx["x"] = self.x + dither
            ctx["v"] = velocity(self.t, ctx["x"], self.resolution_x)
        for effect in self.effect_objects:
            ctx = effect.body_motion(self, p, ctx)
        v_slip = ctx["v"]
        for effect in self.effect_objects:
            v_slip = effect.slip_velocity(self, p, v_slip)
        Fc, Fs = self._levels(p, ctx["d"] < 0)
        log_speed = self.log_speed if v_slip is self.v else None
        g = stribeck_kernel(v_slip, Fc, Fs, p["V"], p["delta"], log_speed)
        for effect in self.effect_objects:
            g = effect.scale_g(self, p, g)
        target = ctx["d"] * g
        for effect in self.effect_objects:
            target = target + effect.target(self, p, ctx["v"])
        F = self._presliding(ctx, np.asarray(target, dtype=float), p["s"])
        for effect in self.effect_objects:
            F = effect.sensor(self, p, F, ctx)
        return F

    def sliding_rows(self):
        speed = np.abs(self.v)
        return speed >= np.median(speed)

    def regressor_speed(self):
        return self.v

    def signed_direction(self):
        return self.d

    def direction_counts(self):
        moving = np.abs(self.v) >= 0.05 * self.scales.speed
        d = self.d[moving]
        return int(np.count_nonzero(d > 0)), int(np.count_nonzero(d < 0)), int(d.size)

    def _last_reversal(self):
        """Index of the sample before each row's last reversal (0 before the first)."""
        change = np.flatnonzero(np.diff(self.d) != 0) + 1
        start = np.zeros(self.x.size, dtype=int)
        start[change] = change
        start = np.maximum.accumulate(start)
        return np.maximum(start - 1, 0), start > 0

    def resolution_noise(self, params, seed=0) -> float:
        """RMS force error [N] that the resolution of x alone causes in the model.

        An encoder's true position lies within a count of its reading (±q/2 of
        rounding, and readings that jitter by a count), a noisy x's within its noise
        std; the model is run on positions drawn that way (uniform within ±q, Gaussian)
        and compared with its run on the record.
        """
        if self.resolution_x == 0:
            return 0.0
        rng = np.random.default_rng(seed)
        if self.quantum_x > 0:
            dither = self.quantum_x * 2.0 * (rng.random(self.x.size) - 0.5)
        else:
            dither = self.noise_x * rng.standard_normal(self.x.size)
        diff = self.predict(params, dither) - self.predict(params)
        return float(np.sqrt(np.mean(diff**2)))

    def after_reversal(self, reach):
        """Rows within ``reach`` [m] of their last reversal (none before the first)."""
        last, reversed_ = self._last_reversal()
        return (np.abs(self.x - self.x[last]) <= reach) & reversed_

    def variables(self):
        last, _ = self._last_reversal()
        return {"x": self.x, "x - x_r": self.x - self.x[last], "v": self.v, "t": self.t,
                "time since reversal": self.t - self.t[last], "direction": self.d}


class SteadyProblem(Problem):
    """(E2) at the measured speeds (MODEL.md §6 ``steady``)."""

    kind = "steady"
    base_names = ("Fc", "Fs", "V", "delta")

    def __init__(self, data, effects=(), fixed=None):
        self.v = data.columns["v"]
        with np.errstate(divide="ignore"):
            self.log_speed = np.log(np.abs(self.v))
        self.measured = data.columns["F"]
        self.scales = Scales(_robust_scale(self.measured), _robust_scale(self.v))
        super().__init__(data, effects, fixed)

    def predict(self, p):
        Fc, Fs = self._levels(p, self.v < 0)
        F = np.sign(self.v) * stribeck_kernel(self.v, Fc, Fs, p["V"], p["delta"], self.log_speed)
        for effect in self.effect_objects:
            F = F + effect.target(self, p, self.v)
        for effect in self.effect_objects:
            F = effect.sensor(self, p, F, {})
        return F

    def regressor_speed(self):
        return self.v

    def signed_direction(self):
        return np.sign(self.v)

    def variables(self):
        return {"v": self.v, "direction": np.sign(self.v)}


class BreakawayProblem(Problem):
    """(E13) with F̂ = avg at z* = 0.95 (MODEL.md §6 ``breakaway``).

    With fewer than three distinct rates only the level is determined: the problem is
    then built with ``level_only`` (Fc tied to Fs, V and δ held) by :func:`problem_for`.
    """

    kind = "breakaway"
    base_names = ("Fc", "Fs", "V", "delta")

    def __init__(self, data, effects=(), fixed=None, level_only=False):
        self.k = data.columns["k"]
        self.measured = data.columns["F_ba"]
        self.s = data.meta_float("s", 1.0)
        if not self.s > 0:
            line = data.meta_lines.get("s")
            where = f"line {line}: " if line else ""
            raise ValueError(f"{where}metadata s must be > 0, got {self.s:g}")
        self.direction = data.columns.get("direction", np.ones_like(self.k))
        self.dwell = data.columns.get("dwell", np.zeros_like(self.k))
        self.distinct_rates = int(np.unique(self.k).size)
        force = _robust_scale(self.measured)
        rate = float(np.max(self.k))
        # the acceleration an inertial term meets at break-away, at the highest rate: the
        # scale of m_e's range (1 m/s² would make its range so wide that a significant
        # m_e of 1e-8 kg read as sitting on the lower bound)
        self.scales = Scales(force, float(e12_velocity(rate, force, self.s, BREAKAWAY_Z)),
                             accel=float(e12_acceleration(rate, force, self.s, BREAKAWAY_Z)),
                             dwell=float(np.max(self.dwell)), rate=rate)
        self.level_only = level_only
        if level_only:
            # g is flat when Fc = Fs: V and δ drop out; held at neutral values
            fixed = {"V": self.scales.speed, "delta": 1.0, **(fixed or {})}
        super().__init__(data, effects, fixed)

    def F_hat(self, Fc, Fs):
        """The 'avg' reading of F̂ in E13."""
        return Fc + (Fs - Fc) / 2

    def speed_at_breakaway(self, p):
        """ẋ* of (E12) at z* for the base levels of ``p`` [m/s]."""
        return e12_velocity(self.k, self.F_hat(p["Fc"], p["Fs"]), self.s, BREAKAWAY_Z)

    def predict(self, p):
        Fc, Fs = self._levels(p, self.direction < 0)
        F_hat = self.F_hat(Fc, Fs)
        speed = e12_velocity(self.k, F_hat, self.s, BREAKAWAY_Z)
        F = stribeck_kernel(speed, Fc, Fs, p["V"], p["delta"])
        for effect in self.effect_objects:
            F = F + effect.target(self, p, speed)
        ctx = {"F_hat": F_hat, "speed": speed}
        for effect in self.effect_objects:
            F = effect.sensor(self, p, F, ctx)
        return F

    def regressor_speed(self):
        return self.k

    def signed_direction(self):
        return self.direction

    def direction_counts(self):
        if "direction" not in self.data.columns:
            return None
        return super().direction_counts()

    def variables(self):
        out = {"k": self.k}
        if "dwell" in self.data.columns:
            out["dwell"] = self.dwell
        if "direction" in self.data.columns:
            out["direction"] = self.direction
        return out


PROBLEMS = {cls.kind: cls for cls in (TimeseriesProblem, SteadyProblem, BreakawayProblem)}


def problem_for(data: Dataset, effects=(), fixed=None) -> Problem:
    """The :class:`Problem` of ``data``'s kind with ``effects``.

    Break-away data at fewer than three distinct rates get a level-only problem
    (MODEL.md §8 ``single-rate``).
    """
    if data.kind == "breakaway":
        level_only = np.unique(data.columns["k"]).size < MIN_RATES
        return BreakawayProblem(data, effects, fixed, level_only=level_only)
    return PROBLEMS[data.kind](data, effects, fixed)


__all__ = ["BreakawayProblem", "PROBLEMS", "Problem", "Scales", "SteadyProblem",
           "TimeseriesProblem", "problem_for"]
