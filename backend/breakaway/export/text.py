"""What every exported file says about the model: its equations, units, effects and
discretisation, and its constants with their units."""

from __future__ import annotations

from .model import ExportModel

#: The exported constants: name in the code, report key, what it is.
CONSTANTS = (
    ("FC", "Fc", "Coulomb level"),
    ("FS", "Fs", "Stribeck (stiction) level"),
    ("V", "V", "Stribeck velocity"),
    ("DELTA", "delta", "Stribeck shape exponent"),
    ("S", "s", "presliding scale; 1/S is the presliding distance"),
    ("SIGMA", "sigma", "viscous coefficient (0: none)"),
    ("N", "n", "exponent of the viscous term (viscous-power; 1: linear)"),
    ("FC_NEG", "Fc_neg", "Coulomb level where the motion is negative (asymmetry)"),
    ("FS_NEG", "Fs_neg", "Stribeck level where the motion is negative (asymmetry)"),
    ("ALPHA", "alpha", "drift of g: g*(1 + ALPHA*(t - T_0)) (0: none)"),
    ("T_0", "t_0", "the time the drift refers to (the record's first sample)"),
)


def ascii_units(text: str) -> str:
    """Units without the middle dot and superscripts (for C comments)."""
    return text.replace("·", "*").replace("²", "^2")


def constants(model: ExportModel, ascii: bool = False) -> list[tuple[str, str, str]]:
    """(name, value as a round-trip literal, comment with the unit) for each constant."""
    params, out = model.params(), []
    for name, key, what in CONSTANTS:
        unit = model.units.get(key, "")
        unit = f" [{ascii_units(unit) if ascii else unit}]" if unit else " [-]"
        out.append((name, repr(float(params[key])), what + unit))
    return out


def header_lines(model: ExportModel, ascii: bool = False) -> list[str]:
    """The description every exported file starts with."""
    u = {key: ascii_units(value) if ascii else value for key, value in model.units.items()}
    rotary = (" (rotary: angles, angular velocities and torques)" if model.rotary else "")
    included = ", ".join(model.effects) or "none"
    lines = [
        "Model (equation numbers of M. Ruderman's note on break-away forces; the effects",
        "as Breakaway's identification names them):",
        "  g(v)   = Fc + (Fs - Fc)*exp(-(|v|/V)^delta), times (1 + alpha*(t - t_0))   (E2)",
        "  Fss(v) = sgn(v)*g(v) + sigma*sgn(v)*|v|^n                                   (E2)",
        "  f(z)   = z*(1 - ln z), z = min(s*|x - x_r|, 1)                              (E4)",
        "  F      = F_r + (d*g(v) + sigma*sgn(v)*|v|^n - F_r)*f(z)                     (E6')",
        "  with Fc_neg, Fs_neg in place of Fc, Fs where the motion is negative.",
        f"Units: x [{u['x']}], v [{u['v']}], t [{u['t']}], F [{u['F']}]{rotary}.",
        f"Effects of the fit included: {included}.",
    ]
    for effect, reason in model.left_out:
        lines.append(f"Left out: {effect} ({reason}).")
    lines += [
        "step(x, t) sees each sample once: v is the backward difference",
        "(x - x_prev)/(t - t_prev), 0 at the first sample (the fit used the central",
        "difference numpy.gradient(x, t)); d is the sign of the increment, kept where it",
        "is zero, and the first motion sets it without a reversal; a reversal starts a",
        "new branch from the previous sample's x and F. The state starts virgin",
        "(x_r = the first x, F_r = 0).",
    ]
    return lines


__all__ = ["CONSTANTS", "ascii_units", "constants", "header_lines"]
