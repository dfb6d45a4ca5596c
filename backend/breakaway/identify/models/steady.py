"""(E2) at measured speeds."""

from __future__ import annotations

import numpy as np

from ...steady import stribeck_kernel
from .base import Problem, Scales, _robust_scale


class SteadyProblem(Problem):
    """(E2) at the measured speeds."""

    kind = "steady"
    base_names = ("Fc", "Fs", "V", "delta")

    def __init__(self, data, effects=(), fixed=None, ties=None):
        self.v = data.columns["v"]
        with np.errstate(divide="ignore"):
            self.log_speed = np.log(np.abs(self.v))
        self.measured = data.columns["F"]
        self.scales = Scales(_robust_scale(self.measured), _robust_scale(self.v))
        super().__init__(data, effects, fixed, ties)

    def predict(self, p):
        Fc, Fs = self._levels(p, self.v < 0)
        F = np.sign(self.v) * stribeck_kernel(self.v, Fc, Fs, p["V"], p["delta"], self.log_speed)
        for effect in self.effect_objects:
            F = F + effect.target(self, p, self.v)
        for effect in self.effect_objects:
            F = effect.sensor(self, p, F, {})
        return F

    def curve_speeds(self, params):
        return np.abs(self.v)

    def regressor_speed(self):
        return self.v

    def signed_direction(self):
        return np.sign(self.v)

    def variables(self):
        return {"v": self.v, "direction": np.sign(self.v)}
