"""The exported model evaluated with the package's own functions: what the generated
Python and C files must reproduce.

The exported ``step(x, t)`` is streaming: it sees each sample once, so it cannot take
the reference discretisation's central difference ``numpy.gradient(x, t)``, which needs the next sample.
It takes the backward difference ``v_i = (x_i − x_{i−1})/(t_i − t_{i−1})`` (``v_0 = 0``);
everything else is the reference discretisation's: ``d_i`` is the sign of the increment
(kept where it is zero; the first non-zero increment sets ``d`` without a reversal,
as the reference's ``d_0``), a reversal at sample i sets ``x_r = x_{i−1}``, ``F_r = F_{i−1}``, and
the run starts virgin (``x_r = x_0``, ``F_r = 0``). Here the same discretisation runs
on whole arrays through :func:`breakaway.presliding.presliding_force_from_target`.
"""

from __future__ import annotations

import numpy as np

from ..presliding import motion_direction, presliding_force_from_target
from ..steady import stribeck_kernel
from .model import ExportModel


def backward_velocity(t, x):
    """``v_i = (x_i − x_{i−1})/(t_i − t_{i−1})``, ``v_0 = 0`` [m/s]; t strictly increasing."""
    t, x = np.asanyarray(t, dtype=float), np.asanyarray(x, dtype=float)
    dt = np.diff(t)
    if np.any(~(dt > 0)):
        raise ValueError("t must be strictly increasing")
    v = np.zeros(x.size)
    v[1:] = np.diff(x) / dt
    return v


def _magnitude(model: ExportModel, v, negative, t):
    """g(v) of (E2) with the levels of the direction, times the drift factor."""
    Fc_neg, Fs_neg = model.levels_negative
    Fc = np.where(negative, Fc_neg, model.Fc)
    Fs = np.where(negative, Fs_neg, model.Fs)
    g = stribeck_kernel(v, Fc, Fs, model.V, model.delta)
    return g * (1.0 + model.alpha * (np.asanyarray(t, dtype=float) - model.t_0))


def _viscous(model: ExportModel, v):
    """σ·sgn(v)·|v|ⁿ (n = 1: σ·v) [N]."""
    return model.sigma * np.sign(v) * np.abs(v) ** model.n


def steady_force(model: ExportModel, v, t=None):
    """The exported steady curve Fss(v) [N] at time t (default t_0), vectorised."""
    v = np.asanyarray(v, dtype=float)
    t = model.t_0 if t is None else t
    return np.sign(v) * _magnitude(model, v, v < 0, t) + _viscous(model, v)


def streaming_force(model: ExportModel, t, x):
    """(E6') along samples (t_i, x_i) as the exported ``step(x, t)`` computes it [N]."""
    t, x = np.asanyarray(t, dtype=float), np.asanyarray(x, dtype=float)
    v = backward_velocity(t, x)
    d = motion_direction(x)
    target = d * _magnitude(model, v, d < 0, t) + _viscous(model, v)
    return presliding_force_from_target(x, target, model.s, 0.0, direction=d)


__all__ = ["backward_velocity", "steady_force", "streaming_force"]
