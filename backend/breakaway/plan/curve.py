"""The steady curve's magnitude and its derivatives, which every measurement family
differentiates through.

``m(v) = g(v) + σ·vⁿ`` for a speed ``v ≥ 0`` with ``g(v) = Fc + (Fs − Fc)·exp(−(v/V)^δ)``
(E2; ``n = 1`` is the viscous term σ·v, other ``n`` the viscous-power effect). The
derivatives are taken in the planner's coordinates: ``ln V`` and ``ln s`` for the two
scales that span decades, the others as they are.
"""

from __future__ import annotations

import numpy as np

#: The parameters the planner models, in the order its matrices use.
PARAMETERS = ("Fc", "Fs", "V", "delta", "s", "sigma", "n")
#: Parameters carried as their logarithm (scales over decades).
LOG_PARAMETERS = frozenset({"V", "s"})
#: How a sentence writes a parameter's key.
SYMBOLS = {"delta": "δ", "sigma": "σ"}


def symbol(name: str) -> str:
    """The symbol a sentence uses for the parameter key ``name`` (δ for delta)."""
    return SYMBOLS.get(name, name)


def magnitude(v, P):
    """``m(v)``, ``dm/dv`` and ``∂m/∂θ`` of the steady curve at speeds ``v ≥ 0``.

    Parameters
    ----------
    v : array_like
        Speeds [m/s], ``v ≥ 0``; broadcast against the parameters.
    P : dict of array_like
        ``Fc``, ``Fs`` [N], ``V`` [m/s], ``delta`` [-], ``sigma`` [N·(s/m)ⁿ] and ``n`` [-],
        each broadcastable against ``v`` (one value per draw of the parameters).

    Returns
    -------
    value : numpy.ndarray
        m(v) [N].
    slope : numpy.ndarray
        dm/dv [N·s/m].
    partial : dict of numpy.ndarray
        ∂m/∂θ for θ in ``Fc``, ``Fs``, ``V`` (per unit of ln V), ``delta``, ``sigma``, ``n``.
    """
    v = np.asanyarray(v, dtype=float)
    Fc, Fs, V, delta = P["Fc"], P["Fs"], P["V"], P["delta"]
    sigma, n = P["sigma"], P["n"]
    drop = Fs - Fc
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        log_ratio = np.log(v / V)
        y = np.exp(delta * log_ratio)  # (v/V)^δ: 0 at rest for δ > 0, inf for δ < 0
        decay = np.exp(-y)
        # y·e^(−y) and y·ln(v/V)·e^(−y) vanish at rest and far out; never 0·inf
        weight = np.where((y > 0) & np.isfinite(y), y * decay, 0.0)
        shape = np.where(weight > 0, weight * log_ratio, 0.0)
        power = np.where(v > 0, np.exp(n * np.log(v)), 0.0)
        slope_g = np.where(v > 0, -drop * delta * weight / v, 0.0)
        slope_viscous = np.where(v > 0, sigma * n * power / np.where(v > 0, v, 1.0), 0.0)
        log_v = np.where(v > 0, np.log(np.where(v > 0, v, 1.0)), 0.0)
    value = Fc + drop * decay + sigma * power
    partial = {
        "Fc": 1.0 - decay,
        "Fs": decay,
        "V": drop * delta * weight,
        "delta": -drop * shape,
        "sigma": power,
        "n": sigma * power * log_v,
    }
    shape_of = np.broadcast_shapes(value.shape, *(np.shape(a) for a in partial.values()))
    partial = {name: np.broadcast_to(a, shape_of) for name, a in partial.items()}
    return value, slope_g + slope_viscous, partial


__all__ = ["LOG_PARAMETERS", "PARAMETERS", "SYMBOLS", "magnitude", "symbol"]
