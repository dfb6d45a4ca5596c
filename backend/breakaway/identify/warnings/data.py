"""Warnings about the recording itself: ``quantised``, ``force-is-command``,
``one-direction`` and ``single-rate``."""

from __future__ import annotations

import math

import numpy as np

from ..effects import EFFECTS
from ..noise import NoiseFloor
from . import warning


def data_warnings(problem, noise: NoiseFloor, inputs: float = 0.0) -> list[dict]:
    """What the columns say about how the data were taken; ``inputs`` is the share of
    the prediction error [N] that x's resolution sets (the report's ``input_floor``)."""
    return [*_quantised(problem, noise, inputs), *_command(problem, noise, inputs),
            *_one_direction(problem), *_single_rate(problem)]


def _quantised(problem, noise: NoiseFloor, inputs: float) -> list[dict]:
    out = []
    unit, length = problem.data.unit("N"), problem.data.unit("m")
    q_x = getattr(problem, "quantum_x", 0.0)
    if q_x > 0:
        part = (f"; through the model they set {inputs:.3g} {unit} of the prediction "
                f"error (the input floor)" if inputs > 0 else "")
        out.append(warning("quantised", "x", (
            f"x takes steps of {q_x:.4g} {length}: direction changes of up to "
            f"{problem.hysteresis:.4g} {length} "
            f"(3 steps) are not reversals, and v is taken over a window of several "
            f"samples{part}")))
    if noise.quantum_F > 0:
        floor = noise.quantum_F / math.sqrt(12)
        column = "F_ba" if problem.kind == "breakaway" else "F"
        out.append(warning("quantised", column, (
            f"{column} takes steps of {noise.quantum_F:.4g} {unit}: the noise floor is not "
            f"taken below q/√12 = {floor:.4g} {unit}")))
    return out


def _command(problem, noise: NoiseFloor, inputs: float) -> list[dict]:
    if not noise.command:
        return []
    unit, length = problem.data.unit("N"), problem.data.unit("m")
    q_x, noise_x = getattr(problem, "quantum_x", 0.0), getattr(problem, "noise_x", 0.0)
    error = (f"its steps of {q_x:.3g} {length}" if q_x > 0
             else f"a noise std of about {noise_x:.3g} {length}")
    floor = (f"the noise floor {noise.value:.4g} {unit} is what the column carries from "
             f"x's reading: it steps where the reading ticks, as a force computed from x "
             f"does and a measured one does not" if noise.method == "carried from x"
             else f"the noise floor {noise.value:.4g} {unit} is the force's own resolution")
    return [warning("force-is-command", "F", (
        f"the force column is a command, not a measurement (no noise above its resolution, "
        f"differences estimate {noise.smooth_F:.3g} {unit}): the measurement error sits in x "
        f"({error}), which sets {inputs:.3g} {unit} of the prediction error through the "
        f"model (the input floor); {floor}"))]


def _one_direction(problem) -> list[dict]:
    counts = problem.direction_counts()
    if counts is None or problem.kind == "breakaway":
        return []
    pos, neg, total = counts
    reason = EFFECTS["asymmetry"].unavailable(problem)
    if not (reason and reason.startswith("one-direction")):
        return []
    share = 100 * min(pos, neg) / max(total, 1)
    return [warning("one-direction", None, (
        f"motion is essentially in one direction ({pos} rows positive, {neg} negative, "
        f"{share:.2g} % the other way): offset and asymmetry are not tried, since "
        f"an offset and the level cannot be separated without both directions"))]


def _single_rate(problem) -> list[dict]:
    if not (problem.kind == "breakaway" and problem.level_only):
        return []
    rates = ", ".join(f"{k:g}" for k in np.unique(problem.k))
    return [warning("single-rate", None, (
        f"break-away measured at {problem.distinct_rates} distinct rate(s) (k = {rates}): "
        f"only the level is determined; it is reported as Fs (= Fc), and V and δ are "
        f"not determined"))]


__all__ = ["data_warnings"]
