"""(E13) at measured rates."""

from __future__ import annotations

import numpy as np

from ...quasistatic import e12_acceleration, e12_velocity
from ...steady import stribeck_kernel
from ..effects import BREAKAWAY_Z
from .base import Problem, Scales, _robust_scale


class BreakawayProblem(Problem):
    """(E13) with F̂ = avg at z* = 0.95.

    With fewer than three distinct rates only the level is determined: the problem is
    then built with ``level_only`` (Fc tied to Fs, V and δ held) by :func:`problem_for`.
    """

    kind = "breakaway"
    base_names = ("Fc", "Fs", "V", "delta")

    def __init__(self, data, effects=(), fixed=None, ties=None, level_only=False):
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
        super().__init__(data, effects, fixed, ties)

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

    def curve_speeds(self, params):
        return np.abs(self.speed_at_breakaway(params))

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
