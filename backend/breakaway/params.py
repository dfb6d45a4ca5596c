"""Model parameters: defaults, presets and validation (the symbols, units and constraints of the model).

All model functions take plain floats; the dictionaries here are the one documented
place where default values live.
"""

from __future__ import annotations

import math
from typing import Mapping

#: Default parameters: the note's Fig. 5 setting, ``Fs = 1.5 Fc``, ``σ = 0``, ``s = 1``.
#: ``V = 100 m/s`` and ``δ = 1`` put the quasi-static break-away velocity of E12
#: (``ẋ* ≈ 19.5·k/F̂`` for ``z* = 0.95``, ``s = 1``) far below ``V`` at ``k = 0.01``
#: (``F_ba ≈ Fs``) and at ~4.7·V at ``k = 30`` (``F_ba`` within 1 % of ``Fc``), so F_ba
#: falls across the whole Fig. 3 range with the Fc, Fs and avg curves apart in between,
#: as in the note's Fig. 5. ``m = 1e-4 kg`` is the small mass of the ramp experiment's worked example.
DEFAULTS: dict[str, float | str] = {
    "Fc": 1.0,  # Coulomb level [N]
    "Fs": 1.5,  # Stribeck (stiction) level [N]
    "V": 100.0,  # Stribeck velocity [m/s]
    "delta": 1.0,  # Stribeck shape exponent [-]
    "sigma": 0.0,  # viscous coefficient [N s/m]
    "s": 1.0,  # presliding scale; 1/s is the presliding distance [1/m]
    "z_ba": 0.95,  # presliding fraction taken as break-away [-]
    "m": 1e-4,  # moving mass of the ramp experiment [kg]
    "k": 1.0,  # actuation force rate [N/s]
    "F_hat": "avg",  # steady-state level used in E12
}

#: Magnitudes the model is evaluated for, in requests and in measured data. Outside
#: them a number is numerically degenerate rather than physical: k = 5e-324 (subnormal)
#: divides by zero in the integrator, V = 5e-324 underflows the Stribeck grid, 1e308
#: overflows the E12 and E13 terms. 1e-30…1e30 holds every physical value in SI (a µN
#: to a MN, a pm/s to a km/s, a ng to a kt) and keeps products and ratios of a few
#: parameters finite.
MAGNITUDE = (1e-30, 1e30)

#: The LuGre comparison model of Canudas de Wit et al. (1995), with the
#: parameters of that paper.
LUGRE_1995: dict[str, float] = {
    "sigma0": 1e5,  # bristle stiffness [N/m]
    "sigma1": math.sqrt(1e5),  # bristle damping [N s/m]
    "sigma2": 0.4,  # viscous coefficient [N s/m]
    "Fc": 1.0,  # [N]
    "Fs": 1.5,  # [N]
    "vs": 1e-3,  # Stribeck velocity [m/s]
    "delta": 2.0,  # [-]
    "m": 1.0,  # [kg]
}

#: The position loop (the loop view and ``POST /api/loop``): the mass,
#: controller and references per friction model, on the model's own parameters
#: (:data:`DEFAULTS` for ``presliding``, normalised units with s = 1; :data:`LUGRE_1995`
#: for ``lugre``, SI). Chosen so that a step hunts within a 5-s run:
#:
#: - presliding: m = 1e-5 kg; Kp = 0.03 N/m, Ki = 3 N/(m·s), Kd = 0.003 N·s/m, a step of
#:   h = 10 presliding distances. The linear loop is stable (Kd·Kp > m·Ki) and
#:   overdamped, so every oscillation is friction's: with Fs = 1.5 Fc it settles into a
#:   stick-slip cycle of ±1.8 around the target with a break-away every 0.65 s (in
#:   alternating directions); with Fs = Fc it settles within 0.003. Kd sits below the
#:   Stribeck curve's steepest fall (Fs − Fc)/V = 0.005 N·s/m, so sliding is unstable:
#:   from Kd = 0.004 on the loop settles, and exact friction compensation from ṙ cuts a
#:   sine's RMS error from 2.5 to 0.4 at Kd = 0.01 (at Kd = 0.003 it raises it from 2.3
#:   to 5.9: the body sticks and slips instead of following ṙ).
#: - lugre: Kp = 2500 N/m, Ki = 1e5 N/(m·s), Kd = 100 N·s/m and a 1-mm step on the 1995
#:   parameters (m = 1 kg): hunting of ±0.09 mm with a break-away every 0.4 s; with
#:   Fs = Fc it settles.
#:
#: ``u_max`` None is no force limit; ``scale`` is the compensation's c (0: off).
LOOP_DEFAULTS: dict[str, dict[str, float | str | None]] = {
    "presliding": {
        "m": 1e-5,  # moving mass [kg]
        "Kp": 0.03,  # proportional gain [N/m]
        "Ki": 3.0,  # integral gain [N/(m s)]
        "Kd": 0.003,  # derivative gain on ṙ − ẋ [N s/m]
        "u_max": None,  # force limit [N]
        "h": 10.0,  # step height, sine amplitude [m]
        "w": 5.0,  # ramp speed [m/s]
        "f": 0.5,  # sine frequency [Hz]
    },
    "lugre": {
        "m": LUGRE_1995["m"],
        "Kp": 2500.0,
        "Ki": 1e5,
        "Kd": 100.0,
        "u_max": None,
        "h": 1e-3,
        "w": 5e-4,
        "f": 0.5,
    },
}
#: What the loop's models share: the reference kind, the run's length [s] and output
#: samples, the compensation scale c, F̂ of the phases' E13 values and z* (LuGre: the
#: fraction of its steady deflection that the bristle reaches at break-away).
LOOP_COMMON: dict[str, float | str] = {
    "kind": "step",
    "duration": 5.0,
    "points": 2000,
    "scale": 0.0,
    "F_hat": "avg",
    "z_ba": 0.95,
}

#: The Fig. 3 rate grid of the note: k = 0.01, 2.01, ..., 28.01 [N/s].
FIG3_RATES: tuple[float, ...] = tuple(0.01 + 2.0 * i for i in range(15))

F_HAT_CHOICES = ("Fc", "Fs", "avg", "self")

#: The explorer's controls, in the order of the form: the one table of each parameter's
#: symbol, unit, slider range and scale (``log``; ``log0``: log with 0 at the left end;
#: ``linear`` with ``step``), help text and fieldset. Served by ``GET /api/presets``.
CONTROLS: tuple[dict[str, float | str], ...] = (
    {"name": "Fc", "symbol": "Fc", "unit": "N", "help": "Coulomb level, > 0",
     "group": "stribeck", "scale": "log", "min": 0.01, "max": 100},
    {"name": "Fs", "symbol": "Fs", "unit": "N", "help": "Stribeck (stiction) level, ≥ Fc",
     "group": "stribeck", "scale": "log", "min": 0.01, "max": 100},
    {"name": "V", "symbol": "V", "unit": "m/s", "help": "Stribeck velocity, > 0",
     "group": "stribeck", "scale": "log", "min": 1e-4, "max": 1e4},
    {"name": "delta", "symbol": "δ", "unit": "", "help": "shape exponent, |δ| ≥ 0.05",
     "group": "stribeck", "scale": "linear", "min": -4, "max": 4, "step": 0.05},
    {"name": "sigma", "symbol": "σ", "unit": "N·s/m",
     "help": "viscous coefficient, ≥ 0 (slider's left end is 0)",
     "group": "stribeck", "scale": "log0", "min": 1e-4, "max": 10},
    {"name": "k", "symbol": "k", "unit": "N/s", "help": "actuation force rate, > 0",
     "group": "presliding", "scale": "log", "min": 0.01, "max": 30},
    {"name": "s", "symbol": "s", "unit": "1/m",
     "help": "presliding scale (1/s is the presliding distance), > 0",
     "group": "presliding", "scale": "log", "min": 0.01, "max": 1e6},
    {"name": "z_ba", "symbol": "z*", "unit": "",
     "help": "presliding fraction taken as break-away, in (0, 1)",
     "group": "presliding", "scale": "linear", "min": 0.01, "max": 0.99, "step": 0.01},
    {"name": "m", "symbol": "m", "unit": "kg", "help": "moving mass of the ramp experiment, > 0",
     "group": "dynamics", "scale": "log", "min": 1e-6, "max": 10},
)

#: Named presets for the explorer (each a full parameter set).
PRESETS: dict[str, dict[str, float | str]] = {
    "fig5": {**DEFAULTS},
    "no-stribeck": {**DEFAULTS, "Fs": 1.0},
    "viscous": {**DEFAULTS, "sigma": 0.001},
    "strengthening": {**DEFAULTS, "delta": -1.0},
    "sharp-stribeck": {**DEFAULTS, "V": 5.0, "delta": 2.0},
    "lugre-1995": {
        **DEFAULTS,
        "Fc": LUGRE_1995["Fc"],
        "Fs": LUGRE_1995["Fs"],
        "V": LUGRE_1995["vs"],
        "delta": LUGRE_1995["delta"],
        "sigma": LUGRE_1995["sigma2"],
        "m": LUGRE_1995["m"],
        # presliding distance of LuGre's bristles: Fs/sigma0 = 15 µm
        "s": LUGRE_1995["sigma0"] / LUGRE_1995["Fs"],
    },
    # a precision linear stage in SI units: 20 µm presliding, a 0.5 kg carriage
    "lab-stage": {
        **DEFAULTS,
        "Fc": 2.0, "Fs": 3.0, "V": 2e-3, "delta": 1.0, "sigma": 20.0, "s": 5e4,
        "m": 0.5, "k": 5.0,
    },
}

#: Presets whose numbers are in the note's normalised units (s = 1: positions in
#: presliding distances, velocities in presliding distances per second); the others
#: are SI.
NORMALISED_PRESETS = frozenset({"fig5", "no-stribeck", "viscous", "strengthening",
                                "sharp-stribeck"})

PRESET_DESCRIPTIONS: dict[str, str] = {
    "fig5": "The note's Fig. 5: Fs = 1.5 Fc, σ = 0, s = 1 (normalised units).",
    "no-stribeck": "Fs = Fc: no velocity weakening, break-away is Fc·f(z*) for every k "
                   "(normalised units).",
    "viscous": "Fig. 5 with viscous friction σ = 0.001: F_ba dips, then rises again at high k "
               "(normalised units).",
    "strengthening": "δ < 0: velocity-strengthening curve, F_ba rises from Fc towards Fs "
                     "(normalised units).",
    "sharp-stribeck": "Narrow Stribeck dip (V = 5, δ = 2): a steep fall of F_ba "
                      "(normalised units).",
    "lugre-1995": "The steady-state curve of the LuGre 1995 paper (vs = 1 mm/s, δ = 2), SI units.",
    "lab-stage": "A precision linear stage in SI units: Fc = 2 N, Fs = 3 N, V = 2 mm/s, "
                 "σ = 20 N·s/m, 20 µm presliding, 0.5 kg.",
}


def _finite(name: str, value: float) -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, got {value}")
    return value


def check_stribeck(Fc: float, Fs: float, V: float, delta: float, sigma: float = 0.0) -> None:
    """Raise ``ValueError`` naming the parameter when the model's constraints fail."""
    Fc, Fs = _finite("Fc", Fc), _finite("Fs", Fs)
    V, delta, sigma = _finite("V", V), _finite("delta", delta), _finite("sigma", sigma)
    if Fc <= 0:
        raise ValueError(f"Fc must be > 0, got {Fc}")
    if Fs < Fc:
        raise ValueError(f"Fs must be >= Fc, got Fs={Fs} < Fc={Fc}")
    if V <= 0:
        raise ValueError(f"V must be > 0, got {V}")
    if delta == 0:
        raise ValueError("delta must be non-zero")
    if sigma < 0:
        raise ValueError(f"sigma must be >= 0, got {sigma}")


def check_positive(**values: float) -> None:
    """Raise ``ValueError`` naming the first parameter that is not finite and > 0."""
    for name, value in values.items():
        if _finite(name, value) <= 0:
            raise ValueError(f"{name} must be > 0, got {value}")


def check_fraction(name: str, value: float) -> None:
    """Raise ``ValueError`` unless ``0 < value < 1``."""
    value = _finite(name, value)
    if not 0 < value < 1:
        raise ValueError(f"{name} must be in (0, 1), got {value}")


def check_f_hat(F_hat: str) -> None:
    if F_hat not in F_HAT_CHOICES:
        raise ValueError(f"F_hat must be one of {F_HAT_CHOICES}, got {F_hat!r}")


def with_defaults(params: Mapping[str, float | str] | None = None, **overrides) -> dict:
    """Return :data:`DEFAULTS` updated by ``params`` and ``overrides``; unknown keys raise."""
    merged = dict(DEFAULTS)
    for source in (params or {}), overrides:
        for key, value in source.items():
            if key not in DEFAULTS:
                raise ValueError(f"unknown parameter {key!r}")
            merged[key] = value
    return merged
