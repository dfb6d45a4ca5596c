"""The note's experiment as a family of runs: force ramps ``u = k·t`` from rest, one
break-away force per run.

Each run measures ``F_ba(k) = m(ẋ*)`` (E13), the steady curve's magnitude at the
break-away speed of (E12), ``ẋ* = k/(s·F̂·|ln z*|)``; ``F̂`` is ``Fc``, ``Fs``, their
mean, or the self-consistent root of ``ẋ·m(ẋ) = k/(s·|ln z*|)``. ``V`` and ``s`` enter
only through ``s·V``. A run yields its measurement only when the body breaks away
before the ramp ends: below the rig's largest force and within the run's time.
"""

from __future__ import annotations

import numpy as np

from ..quasistatic import _self_consistent_velocity
from .curve import magnitude
from .family import Candidates, Information, from_rows
from .programme import empty_csv, ramps_csv, run_order

#: A run yields nothing when its break-away lies this close to the ramp's end (the
#: rig cannot tell a break-away at its last sample from none).
END_MARGIN = 0.999


def _level_weights(F_hat: str) -> tuple[float, float]:
    """(∂F̂/∂Fc, ∂F̂/∂Fs) of a constant level ``F̂``."""
    return {"Fc": (1.0, 0.0), "Fs": (0.0, 1.0), "avg": (0.5, 0.5)}[F_hat]


def breakaway_measurement(k, P, F_hat="avg", z_ba=0.95):
    """F_ba of (E13) at rates ``k`` and its derivatives in the planner's coordinates.

    Parameters
    ----------
    k : array_like
        Force rates [N/s], shape (G,).
    P : dict of array_like
        ``Fc``, ``Fs``, ``V``, ``delta``, ``s``, ``sigma`` (``n`` = 1), each of shape
        (Q, 1): one value per draw.
    F_hat : {'Fc', 'Fs', 'avg', 'self'}
        The level F̂ of (E12).
    z_ba : float
        Presliding fraction z* taken as break-away [-].

    Returns
    -------
    F_ba : numpy.ndarray
        (Q, G) break-away force [N].
    speed : numpy.ndarray
        (Q, G) break-away speed ẋ* [m/s].
    partial : dict of numpy.ndarray
        ∂F_ba/∂θ, (Q, G) each, for Fc, Fs, V (per unit of ln V), delta, s (per unit of
        ln s) and sigma.
    """
    k = np.asarray(k, dtype=float)
    P = {**P, "n": np.ones_like(np.asarray(P["Fc"], dtype=float))}
    reach = -np.log(z_ba)
    work = k / (P["s"] * reach)  # ẋ*·F̂ = k/(s·|ln z*|)
    if F_hat == "self":
        draws = np.shape(P["Fc"])[0]
        work = np.broadcast_to(work, (draws, k.size))
        curve = ("Fc", "Fs", "V", "delta", "sigma")
        speed = np.stack([_self_consistent_velocity(
            work[q], *(float(np.ravel(P[name])[q]) for name in curve)) for q in range(draws)])
    else:
        weight_c, weight_s = _level_weights(F_hat)
        level = weight_c * P["Fc"] + weight_s * P["Fs"]
        speed = work / level
    value, slope, partial = magnitude(speed, P)
    if F_hat == "self":
        # ẋ·m(ẋ) = c: dẋ/dθ = (dc/dθ − ẋ·∂m/∂θ)/(m + ẋ·m')
        rise = value + speed * slope
        moves = {name: -speed * partial[name] / rise for name in ("Fc", "Fs", "V", "delta", "sigma")}
        moves["s"] = -work / rise
    else:
        moves = {"Fc": -speed / level * weight_c, "Fs": -speed / level * weight_s,
                 "V": 0.0, "delta": 0.0, "sigma": 0.0, "s": -speed}
    out = {name: partial.get(name, 0.0) + slope * moves[name] for name in moves}
    return value, speed, {name: np.broadcast_to(a, value.shape) for name, a in out.items()}


class Ramps:
    """Force ramps at chosen rates (the note's experiment)."""

    name = "ramps"
    depends = ("Fc", "Fs", "V", "delta", "s", "sigma")
    header = ("run", "t", "u")
    #: the limits its runs are bound by
    limits = ("u_max", "v_max", "duration")

    def candidates(self, P, setting, middle: int = 0) -> Candidates:
        """Rates from the slowest whose ramp can reach the Coulomb level within a run
        to the fastest whose break-away speed stays below ``v_max`` at every draw."""
        lim = setting.limits
        reach = -np.log(setting.z_ba)
        lowest_level = np.min(P["Fc"])  # F̂ ≥ Fc for every reading
        fastest = lim.v_max * np.min(P["s"]) * lowest_level * reach
        slowest = np.min(P["Fc"]) / lim.duration
        if lim.u_max <= np.min(P["Fc"]):
            return Candidates({}, f"no ramp breaks away below u_max = {lim.u_max:.4g} "
                                  f"{setting.units['F']}: the Coulomb level is "
                                  f"{np.min(P['Fc']):.4g} {setting.units['F']}")
        if slowest >= fastest:
            return Candidates({}, (
                f"no rate both reaches the Coulomb level within a run of {lim.duration:.3g} s "
                f"(k ≥ {slowest:.3g} {setting.units['k']}) and keeps the break-away speed "
                f"below v_max = {lim.v_max:.3g} {setting.units['v']} "
                f"(k ≤ {fastest:.3g} {setting.units['k']})"))
        return Candidates({"k": np.geomspace(slowest, fastest, setting.grid)})

    def end_force(self, k, setting):
        """Where each ramp stops [N]: the force limit, or the force reached in a run."""
        return np.minimum(setting.limits.u_max, np.asarray(k) * setting.limits.duration)

    def information(self, cands: Candidates, P, setting, names, middle: int = 0) -> Information:
        k = cands.points["k"]
        F_ba, speed, partial = breakaway_measurement(k, P, setting.F_hat, setting.z_ba)
        usable = F_ba < END_MARGIN * self.end_force(k, setting)
        return from_rows(partial, names, 1.0 / setting.noise, usable,
                         {"F_ba": F_ba, "speed": speed})

    def design(self, counts, cands: Candidates, info: Information, mid: int, setting) -> dict:
        """The chosen rates (one per run, ascending) with their predicted break-away
        at the middle draw."""
        index = np.repeat(np.arange(counts.size), counts)
        k = cands.points["k"][index]
        return {"rates": k.tolist(),
                "end_force": self.end_force(k, setting).tolist(),
                "predicted_F_ba": info.predicted["F_ba"][mid, index].tolist(),
                "breakaway_speed": info.predicted["speed"][mid, index].tolist()}

    def programme(self, design: dict | None, setting, reason: str = "") -> str:
        if not design or not design["rates"]:
            return empty_csv(self.header, reason)
        order = run_order(len(design["rates"]))
        k = np.asarray(design["rates"])[order]
        return ramps_csv(k, self.end_force(k, setting), setting.units)


__all__ = ["Ramps", "breakaway_measurement"]
