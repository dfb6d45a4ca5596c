"""One redraw of the explorer: every curve the four plots need, from one parameter set."""

from __future__ import annotations

import numpy as np

from .params import FIG3_RATES, F_HAT_CHOICES, check_positive, check_stribeck, with_defaults
from .presliding import hysteresis_loop
from .quasistatic import breakaway_force, phase_family
from .steady import steady_state_force

#: Grid sizes of one frame (the ``/api/explore`` payload; the benchmark's "explorer frame").
FRAME_GRID = {
    "stribeck": 400,  # points of Fss(v)
    "loop": 2000,  # samples of the hysteresis loop
    "phase": 200,  # points per phase curve
    "breakaway": 200,  # rates of the F_ba(k) curves
}


def stribeck_curve(Fc, Fs, V, delta, sigma, n=400, v_max=None):
    """Fss on a symmetric velocity grid ``[-v_max, v_max]`` [m/s] (default 5·V)."""
    check_stribeck(Fc, Fs, V, delta, sigma)  # before V sets the default v_max
    v_max = 5.0 * V if v_max is None else float(v_max)
    check_positive(v_max=v_max)
    v = np.linspace(-v_max, v_max, int(n))
    return v, steady_state_force(v, Fc, Fs, V, delta, sigma)


def breakaway_curves(Fc, Fs, V, delta, s, sigma, z_ba, n=200, k_min=0.01, k_max=30.0):
    """F_ba(k) of (E13) for every F̂ choice on one rate grid [N/s] (the note's Fig. 5)."""
    check_positive(k_min=k_min, k_max=k_max)
    if k_max <= k_min:
        raise ValueError(f"k_max must be > k_min, got {k_max} <= {k_min}")
    k = np.linspace(k_min, k_max, int(n))
    curves = {name: breakaway_force(k, Fc, Fs, V, delta, s, sigma, name, z_ba)
              for name in F_HAT_CHOICES}
    return k, curves


def explore_frame(params=None, grid=None, loop_amplitude=1.5):
    """All four plots of one explorer redraw (the payload of ``POST /api/explore``).

    Parameters
    ----------
    params : dict, optional
        Model parameters (keys of :data:`breakaway.params.DEFAULTS`); omitted ones take
        the defaults.
    grid : dict, optional
        Overrides of :data:`FRAME_GRID`.
    loop_amplitude : float, optional
        Amplitude of the hysteresis excitation in units of ``1/s``.

    Returns
    -------
    dict
        ``stribeck``, ``hysteresis``, ``phase`` (Fig. 3 family plus the current k) and
        ``breakaway`` (F_ba for Fc, Fs, avg, self), as numpy arrays.
    """
    p = with_defaults(params)
    sizes = {**FRAME_GRID, **(grid or {})}
    Fc, Fs, V, delta = p["Fc"], p["Fs"], p["V"], p["delta"]
    s, sigma, z_ba, k = p["s"], p["sigma"], p["z_ba"], p["k"]
    v, F_ss = stribeck_curve(Fc, Fs, V, delta, sigma, sizes["stribeck"])
    x, F_loop = hysteresis_loop(Fc, Fs, V, delta, s, sigma, loop_amplitude, sizes["loop"])
    rates = np.append(np.asarray(FIG3_RATES), float(k))
    z, v_phase = phase_family(Fc, Fs, V, delta, s, sigma, p["F_hat"], rates, sizes["phase"])
    k_grid, curves = breakaway_curves(Fc, Fs, V, delta, s, sigma, z_ba, sizes["breakaway"])
    return {
        "stribeck": {"v": v, "F": F_ss},
        "hysteresis": {"x": x, "F": F_loop},
        "phase": {"z": z, "curves": [{"k": float(r), "v": row} for r, row in zip(rates, v_phase)]},
        "breakaway": {"k": k_grid, **curves},
    }
