"""Where break-away forces carry information about V and δ: the band of rates over
which F_ba(k) changes most with them (the note's Fig. 5 makes the point: the curves
for the different F̂ part only during the exponential decrease).

F_ba(k) is the steady curve at the break-away speed ẋ* = k/(s·F̂·|ln z*|) (E12, E13).
It depends on V and δ only while ẋ* lies within the Stribeck drop: slower ramps break
away at about Fs, faster ones at about Fc, and measure those levels and nothing else.
The band is where the sensitivity √((∂F_ba/∂ln V)² + (∂F_ba/∂ln δ)²) is at least half
its largest value.
"""

from __future__ import annotations

import numpy as np

from .ramps import breakaway_measurement

#: The sensitivity at the band's edges, as a share of its largest value.
BAND_LEVEL = 0.5
#: Rates searched: this many decades either side of where ẋ* = V, this many points.
BAND_DECADES = 6
BAND_POINTS = 1201


def rate_band(Fc, Fs, V, delta, s=1.0, sigma=0.0, F_hat="avg", z_ba=0.95):
    """The rates where F_ba(k) is most sensitive to V and δ.

    Parameters
    ----------
    Fc, Fs, V, delta, s, sigma, F_hat, z_ba :
        The model (E2, E12, E13), units as in :func:`breakaway.quasistatic.breakaway_force`.

    Returns
    -------
    dict or None
        ``k``: [low, high] [N/s], ``speed``: the break-away speeds there [m/s], ``peak``:
        the rate of the largest sensitivity [N/s]; None without a drop (Fs = Fc).
    """
    if Fs <= Fc:
        return None
    level = {"Fc": Fc, "Fs": Fs}.get(F_hat, 0.5 * (Fc + Fs))
    centre = V * s * level * -np.log(z_ba)  # the rate whose ẋ* is V (for constant F̂)
    k = centre * np.logspace(-BAND_DECADES, BAND_DECADES, BAND_POINTS)
    P = {name: np.array([[value]]) for name, value in
         {"Fc": Fc, "Fs": Fs, "V": V, "delta": delta, "s": s, "sigma": sigma}.items()}
    _, speed, partial = breakaway_measurement(k, P, F_hat, z_ba)
    strength = np.hypot(partial["V"][0], delta * partial["delta"][0])
    peak = int(np.argmax(strength))
    inside = strength >= BAND_LEVEL * strength[peak]
    # the contiguous run of rates around the peak
    edges = np.flatnonzero(~inside)
    below = edges[edges < peak]
    above = edges[edges > peak]
    low = int(below[-1]) + 1 if below.size else 0
    high = int(above[0]) - 1 if above.size else k.size - 1
    return {"k": [float(k[low]), float(k[high])],
            "speed": [float(speed[0, low]), float(speed[0, high])],
            "peak": float(k[peak])}


__all__ = ["BAND_LEVEL", "rate_band"]
