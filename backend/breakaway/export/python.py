"""The exported model as a standalone Python module (standard library only)."""

from __future__ import annotations

from string import Template

from .. import __version__
from .model import ExportModel
from .text import constants, header_lines

_MODULE = Template('''"""Friction model exported by breakaway $version from a $kind identification report.

$header
"""

import math

$constants


def _magnitude(v, negative, t):
    """g(v) of (E2) [$F] with the levels of the direction, times the drift factor."""
    fc, fs = (FC_NEG, FS_NEG) if negative else (FC, FS)
    if v == 0.0:
        level = fs if DELTA > 0 else fc  # the limits of g at rest
    else:
        level = fc + (fs - fc) * math.exp(-((abs(v) / V) ** DELTA))
    return level * (1.0 + ALPHA * (t - T_0))


def _viscous(v):
    """SIGMA*sgn(v)*|v|**N [$F] (N = 1: linear viscous friction)."""
    return math.copysign(SIGMA * abs(v) ** N, v)


def _steady_scalar(v, t):
    if v == 0.0:
        return 0.0
    return math.copysign(_magnitude(v, v < 0.0, t), v) + _viscous(v)


def steady(v, t=T_0):
    """Steady-state friction Fss(v) (E2) with the accepted effects [$F].

    v: velocity [$v], a float, a (nested) sequence or a numpy array (returned as the
    same kind); t: time [$t] for the drift, T_0 by default.
    """
    if isinstance(v, (int, float)):
        return _steady_scalar(float(v), t)
    if hasattr(v, "shape") and hasattr(v, "astype"):  # numpy, without importing it
        out = v.astype(float)
        flat = out.reshape(-1)
        for i in range(flat.size):
            flat[i] = _steady_scalar(float(flat[i]), t)
        return out
    return [steady(item, t) for item in v]


class Presliding:
    """Presliding friction with reversal memory (E4, E6'), one sample at a time.

    State: the direction d (+1, -1; 0 before the first motion), the position x_r
    [$x] and friction F_r [$F] at the last reversal, and the previous sample. Starts
    virgin: x_r is the first sample's x, F_r = 0.
    """

    def __init__(self):
        self.reset()

    def reset(self):
        """Back to the virgin state."""
        self.started = False
        self.d = 0
        self.x_r = 0.0
        self.F_r = 0.0
        self.x_prev = 0.0
        self.t_prev = 0.0
        self.F_prev = 0.0

    def step(self, x, t):
        """Friction [$F] at position x [$x] and time t [$t] (t strictly increasing)."""
        x, t = float(x), float(t)
        v = 0.0
        if not self.started:
            self.started = True
            self.x_r = x
        else:
            if not t > self.t_prev:
                raise ValueError(f"t must increase: {t} after {self.t_prev}")
            dx = x - self.x_prev
            v = dx / (t - self.t_prev)  # backward difference
            if dx != 0.0:
                sign = 1 if dx > 0.0 else -1
                if self.d == 0:
                    self.d = sign  # the first motion: no reversal
                elif sign != self.d:  # a reversal: a new branch from the previous sample
                    self.x_r, self.F_r, self.d = self.x_prev, self.F_prev, sign
        target = self.d * _magnitude(v, self.d < 0, t) + _viscous(v)
        z = min(S * abs(x - self.x_r), 1.0)
        shape = z * (1.0 - math.log(z)) if z > 0.0 else 0.0  # f(z) of (E4)
        F = self.F_r + (target - self.F_r) * shape  # (E6')
        self.x_prev, self.t_prev, self.F_prev = x, t, F
        return F
''')


def python_module(model: ExportModel) -> str:
    """The source of a dependency-free Python module with ``steady(v)`` and
    ``class Presliding`` (``step(x, t)``) for ``model``."""
    units = model.units
    return _MODULE.substitute(
        version=__version__, kind=model.kind, header="\n".join(header_lines(model)),
        constants="\n".join(f"{name} = {value}  # {comment}"
                            for name, value, comment in constants(model)),
        F=units["F"], v=units["v"], x=units["x"], t=units["t"])


__all__ = ["python_module"]
