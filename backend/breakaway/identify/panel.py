"""What the explorer's data panel plots: measured F, the base and final models, the
residuals before and after, and the regressor each accepted effect was traced to."""

from __future__ import annotations

import io

import numpy as np

from .diagnosis import Diagnosis
from .effects import EFFECTS

#: The axis of the main plot per kind.
MAIN_AXIS = {"timeseries": "t", "steady": "v", "breakaway": "k"}


def _regressors(diagnosis: Diagnosis) -> dict[str, np.ndarray]:
    problem = diagnosis.base.problem
    kind = diagnosis.data.kind
    if kind == "timeseries":
        return {"t": problem.t, "x": problem.x, "v": problem.v, "a": problem.a}
    if kind == "steady":
        return {"v": problem.v}
    return {"k": problem.k, "direction": problem.direction, "dwell": problem.dwell}


def _columns(diagnosis: Diagnosis) -> dict[str, np.ndarray]:
    """Every row: the regressors, measured F, both models and both residuals."""
    measured = diagnosis.base.problem.measured
    return {
        **_regressors(diagnosis),
        "measured": measured,
        "base": diagnosis.base.prediction,
        "final": diagnosis.final.prediction,
        "residual_before": measured - diagnosis.base.prediction,
        "residual_after": measured - diagnosis.final.prediction,
    }


_CSV_NAMES = {"measured": "F_measured", "base": "F_base", "final": "F_final"}


def series(diagnosis: Diagnosis, max_points: int = 4000) -> dict:
    """Plot data for the panel, every ``stride``-th row so at most ``max_points`` rows.

    Returns
    -------
    dict
        ``axis`` (name of the main x-axis), ``columns`` (regressors, ``measured``,
        ``base``, ``final``, ``residual_before``, ``residual_after`` as lists) and
        ``effect_regressor`` (effect → column name).
    """
    kind = diagnosis.data.kind
    columns = _columns(diagnosis)
    order = np.argsort(columns[MAIN_AXIS[kind]], kind="stable")
    stride = max(1, -(-order.size // max_points))
    keep = order[::stride]
    return {
        "axis": MAIN_AXIS[kind],
        "stride": stride,
        "columns": {name: np.asarray(values, float)[keep].tolist()
                    for name, values in columns.items()},
        "effect_regressor": {e: EFFECTS[e].regressor[kind] for e in diagnosis.effects},
    }


def residuals_csv(diagnosis: Diagnosis) -> str:
    """Every row: the regressors, measured F, both models and both residuals, as CSV."""
    kind = diagnosis.data.kind
    # the file names the force columns as forces
    columns = {_CSV_NAMES.get(name, name): values for name, values in _columns(diagnosis).items()}
    out = io.StringIO()
    out.write(f"# kind: {kind}\n# effects: {' '.join(diagnosis.effects) or 'none'}\n")
    out.write(",".join(columns) + "\n")
    np.savetxt(out, np.column_stack(list(columns.values())), delimiter=",", fmt="%.9g")
    return out.getvalue()
