"""The ramp experiment (E7) at one rate, as time series, beside E13.

What the explorer's ramp view and ``POST /api/ramp`` show: the actuation u = k·t, the
friction F, x, ẋ and z over the run up to break-away, the break-away instant, and the
quasi-static break-away force (E13) for the same parameters.
"""

from __future__ import annotations

import math

import numpy as np

from .dynamics import simulate_lugre_trajectory, simulate_trajectory
from .params import DEFAULTS
from .quasistatic import breakaway_force

#: Samples returned at most (the run is thinned evenly, break-away kept).
MAX_POINTS = 2000


def presliding_z(x, v, s):
    """``z = s·|x − x_r|`` along a simulated run [-] (E5).

    Parameters
    ----------
    x : array_like
        Position [m].
    v : array_like
        Velocity ẋ [m/s], same shape; samples with ẋ = 0 keep the last direction.
    s : float
        Presliding scale [1/m].

    Returns
    -------
    numpy.ndarray
        z, where x_r is the position at the last change of sign of ẋ (x_r = 0 from rest,
        the virgin state). Vectorised: a run holds up to 200,000 samples.
    """
    x = np.asanyarray(x, dtype=float)
    sign = np.sign(np.asanyarray(v, dtype=float))
    moving = np.flatnonzero(sign)
    turned = moving[1:][sign[moving[1:]] != sign[moving[:-1]]]
    last_turn = np.full(x.size, -1)
    last_turn[turned] = turned
    last_turn = np.maximum.accumulate(last_turn)
    x_r = np.where(last_turn >= 0, x[np.maximum(last_turn, 0)], 0.0)
    return s * np.abs(x - x_r)


def _thin(n, max_points):
    if n <= max_points:
        return np.arange(n)
    keep = np.unique(np.linspace(0, n - 1, max_points).round().astype(int))
    return keep


def ramp_experiment(model: str, k: float, params: dict, max_steps: int,
                    max_points: int = MAX_POINTS) -> dict:
    """One ramp run of ``model`` (``presliding``: E7 with E6'; ``lugre``) at rate ``k``.

    Parameters
    ----------
    model : {'presliding', 'lugre'}
    k : float
        Actuation force rate [N/s].
    params : dict
        ``simulate_trajectory`` keyword arguments (presliding: Fc, Fs, V, delta, sigma, s,
        m, z_ba, and optionally F_hat for E13) or LuGre's parameters (``lugre``).
    max_steps : int
        Step budget of the integrator.

    Returns
    -------
    dict
        ``t, x, v, u, F, z`` lists, ``t_ba, u_ba, F_ba`` (None when no break-away within
        the budget), ``E13`` [N], ``reversals``.
    """
    params = dict(params)
    F_hat = params.pop("F_hat", DEFAULTS["F_hat"])
    if model == "lugre":
        run = simulate_lugre_trajectory(k, params, max_steps=max_steps)
        z = run.bristle
        E13 = breakaway_force(k, params["Fc"], params["Fs"], params["vs"], params["delta"],
                              DEFAULTS["s"], params["sigma2"], F_hat, DEFAULTS["z_ba"])
    else:
        run = simulate_trajectory(k, max_steps=max_steps, **params)
        z = presliding_z(run.x, run.v, params["s"])
        E13 = breakaway_force(k, params["Fc"], params["Fs"], params["V"], params["delta"],
                              params["s"], params["sigma"], F_hat, params["z_ba"])
    keep = _thin(run.t.size, max_points)
    broke = math.isfinite(run.t_ba)
    return {
        "t": run.t[keep].tolist(), "x": run.x[keep].tolist(), "v": run.v[keep].tolist(),
        "u": run.u[keep].tolist(), "F": run.F[keep].tolist(), "z": z[keep].tolist(),
        "t_ba": float(run.t_ba) if broke else None,
        "u_ba": float(k * run.t_ba) if broke else None,
        "F_ba": float(run.F_ba) if broke else None,
        "E13": float(E13),
        "reversals": int(run.reversals),
    }


__all__ = ["MAX_POINTS", "presliding_z", "ramp_experiment"]
