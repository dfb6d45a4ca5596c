"""The effect library of MODEL.md §7: names, parameters and the kinds they apply to.

The forward models that use them live in :mod:`breakaway.identify.models`; the residual
signatures that point to them in :mod:`breakaway.identify.signatures`.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Effect:
    """One effect the base model lacks.

    Attributes
    ----------
    name : str
        Fixed name used in reports and tests.
    params : tuple of str
        The report's keys of its extra parameters.
    kinds : tuple of str
        Data kinds it applies to.
    needs : tuple of str
        Optional data columns it needs (e.g. ``dwell``).
    description : str
        One line for people.
    """

    name: str
    params: tuple[str, ...]
    kinds: tuple[str, ...]
    needs: tuple[str, ...] = ()
    description: str = ""


EFFECTS: dict[str, Effect] = {e.name: e for e in (
    Effect("viscous", ("sigma",), ("timeseries", "steady", "breakaway"),
           description="viscous friction σ·v added to the steady state"),
    Effect("asymmetry", ("Fc_neg", "Fs_neg"), ("timeseries", "steady", "breakaway"),
           description="separate Coulomb and Stribeck levels in the negative direction"),
    Effect("offset", ("F_offset",), ("timeseries", "steady"),
           description="a constant bias of the force sensor"),
    Effect("drift", ("alpha",), ("timeseries",),
           description="friction level drifting linearly in time (wear, temperature)"),
    Effect("inertia", ("m_e",), ("timeseries", "breakaway"),
           description="an inertial force m_e·a in the measured force"),
    Effect("ripple", ("A", "wavelength", "phase"), ("timeseries",),
           description="position-dependent friction A·sin(2πx/λ + φ)"),
    Effect("lag", ("tau",), ("timeseries",),
           description="frictional lag: the Stribeck level follows a filtered velocity"),
    Effect("backlash", ("play",), ("timeseries",),
           description="a play of width b between the measured point and the sliding body"),
    Effect("dwell", ("zeta", "tau_d"), ("breakaway",), needs=("dwell",),
           description="stiction rising with the dwell time before the ramp"),
)}


#: Rows needed in each direction before separate negative-direction levels can be fitted.
MIN_ROWS_PER_DIRECTION = 5


def _both_directions(kind: str, columns) -> bool:
    import numpy as np

    if kind == "steady":
        v = np.asarray(columns["v"])
    elif kind == "breakaway":
        if "direction" not in columns:
            return False
        v = np.asarray(columns["direction"])
    else:
        v = np.diff(np.asarray(columns["x"]))
    return min(np.count_nonzero(v > 0), np.count_nonzero(v < 0)) >= MIN_ROWS_PER_DIRECTION


def candidates(kind: str, columns) -> list[str]:
    """Effects of the library that apply to ``kind`` and that the data can determine:
    the columns they need are there, ``asymmetry`` sees motion both ways and ``dwell``
    at least two dwell times."""
    names = []
    for effect in EFFECTS.values():
        if kind not in effect.kinds or not all(c in columns for c in effect.needs):
            continue
        if effect.name == "asymmetry" and not _both_directions(kind, columns):
            continue
        if effect.name == "dwell" and len(set(map(float, columns["dwell"]))) < 2:
            continue  # one dwell time only rescales Fs
        names.append(effect.name)
    return names
