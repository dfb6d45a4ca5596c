"""What a record spans: its largest force and speed, the speeds at which it shows the
steady curve, its rates, travel, length and sampling rate.

The report carries this as ``extent``, so that what comes after a fit (the plan of
the next experiment, the data panel's limits) knows the record without reading it
again: the largest force and speed a rig reached are the natural first guess of its
limits, and the slowest and fastest speeds at which the curve is shown bound what the
data leave open.
"""

from __future__ import annotations

import numpy as np

from .fitting import FitResult


def _span(values) -> list[float] | None:
    values = np.asarray(values, dtype=float)
    return [float(np.min(values)), float(np.max(values))] if values.size else None


def record_extent(fit: FitResult) -> dict:
    """The extent of the record ``fit`` was made on, in the record's units.

    Returns
    -------
    dict
        ``force``: the largest |measured force| [N]; ``speed``: the largest speed the
        record reached [m/s] (at break-away, for break-away data: ẋ* of E12 at the
        fastest rate); ``speeds``: [slowest, fastest] speed at which the data show the
        steady curve (E2) under the fitted model, or None; ``held_force``: the largest
        force held without gross sliding [N] or None; and per kind ``rates`` [N/s]
        (breakaway), ``travel`` [m], ``duration`` [s] and ``sample_rate`` [Hz]
        (timeseries).
    """
    pb, p = fit.problem, fit.params
    shown = pb.curve_speeds(p)
    held = pb.held_force(p)
    extent = {"force": float(np.max(np.abs(pb.measured))),
              "speed": float(np.max(np.abs(pb.regressor_speed())))
              if pb.kind != "breakaway" else float(np.max(shown)),
              "speeds": _span(shown),
              "held_force": None if held is None else float(max(held))}
    if pb.kind == "breakaway":
        extent["rates"] = _span(pb.k)
    if pb.kind == "timeseries":
        t = pb.t
        extent["travel"] = float(np.ptp(pb.x))
        extent["duration"] = float(t[-1] - t[0])
        steps = np.diff(t)
        extent["sample_rate"] = float(1.0 / np.median(steps)) if steps.size else None
    return extent


__all__ = ["record_extent"]
