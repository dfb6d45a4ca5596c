"""``floor-low``: a residual above the noise floor that is noise-like all the same
(the floor, a median, reads the quiet part of uneven noise)."""

from __future__ import annotations

import math

import numpy as np

from ..fitting import FitResult
from ..residuals import lag_one_correlation
from . import warning

#: Structure is "clear" when the final residual exceeds what its rows are expected to
#: carry by this factor (the RMSE the floor; the report's ``unexplained``:
#: :func:`..input_error.misfit_ratio`, row by row).
UNEXPLAINED_RATIO = 1.3
#: ... unless the residual is noise-like: successive residuals correlate less than this,
#: and no variable explains more than :data:`NOISE_LIKE_SHARE` of it (noise whose
#: spread changes: the floor, a median of differences, reads below its RMS) ...
NOISE_LIKE_CORRELATION = 0.1
#: ... or less than this many times the correlation's standard error for white noise,
#: 1/√pairs, where that is larger: 42 rows of a steady curve correlate ±0.15 by chance.
CHANCE_STDS = 2.0
NOISE_LIKE_SHARE = 0.05
#: Noise is uneven when its RMS in one bin of the rows by some variable (up to ten, of
#: 50 rows or more) is this many times that in another.
UNEVEN_SPREAD = 1.5


def floor_low_warnings(fit: FitResult, floor: float, structure: list[dict]) -> list[dict]:
    """``floor-low`` when the residual exceeds the floor as far as structure would
    (:data:`UNEXPLAINED_RATIO`) but is noise-like (:data:`NOISE_LIKE_CORRELATION`, or
    within chance on few rows, :data:`CHANCE_STDS`): the floor reads low, nothing is
    missing."""
    if not fit.rmse > UNEXPLAINED_RATIO * floor:
        return []
    residual = fit.residual()
    correlation = lag_one_correlation(residual, fit.problem)
    chance = CHANCE_STDS / math.sqrt(max(residual.size - 1, 1))
    strongest = max((item["strength"] for item in structure), default=0.0)
    if abs(correlation) >= max(NOISE_LIKE_CORRELATION, chance) \
            or strongest >= NOISE_LIKE_SHARE:
        return []
    along, ratio = max(((name, spread_ratio(residual, values))
                        for name, values in fit.problem.variables().items()),
                       key=lambda item: item[1], default=(None, 1.0))
    why = (f"its spread changes {ratio:.1f}-fold along {along}, and the floor (a median) "
           "reads the quiet part" if ratio >= UNEVEN_SPREAD
           else "its spread is even, so the floor itself reads low (a median of "
           "differences, or a quantisation's q/√12, misses part of the noise)")
    return [warning("floor-low", None, (
        f"the residual is noise-like (successive values correlate {correlation:+.2f}, no "
        f"variable explains {100 * NOISE_LIKE_SHARE:.0f} % of it) but its RMS, "
        f"{fit.rmse:.3g}, is {fit.rmse / floor:.2f} times the noise floor: {why}; no "
        "effect is missing"))]


def spread_ratio(residual, values) -> float:
    """Largest over smallest RMS of the residual in up to 10 equal-count bins of
    ``values``, of 50 rows or more (fewer rows would read chance as unevenness)."""
    bins = int(np.clip(residual.size // 50, 1, 10))
    order = np.argsort(values, kind="stable")
    rms = [math.sqrt(float(np.mean(part**2))) for part in np.array_split(residual[order], bins)
           if part.size]
    return max(rms) / min(rms) if min(rms) > 0 else math.inf


__all__ = ["CHANCE_STDS", "UNEXPLAINED_RATIO", "floor_low_warnings", "spread_ratio"]
