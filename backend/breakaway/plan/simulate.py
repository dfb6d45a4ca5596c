"""A plan run on a synthetic truth: the measurements its programme would give, with
seeded noise, as a record of the kind the identification reads, and that record
joined to an earlier one, so that a refit on both shows what the plan delivers.

This is how the plan is checked (and how its documentation's example was made): the
truth is known, so the refit's actual errors can be set against the standard errors
the plan predicted.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares

from ..identify.csvdata import Dataset
from ..identify.models import problem_for
from ..presliding import presliding_force
from ..quasistatic import breakaway_force
from ..steady import steady_state_force
from .fisher import verdicts


def _dataset(kind: str, columns: dict, meta: dict | None = None, segments=()) -> Dataset:
    n = len(next(iter(columns.values())))
    meta = dict(meta or {})
    return Dataset(kind=kind, columns={k: np.asarray(v, dtype=float) for k, v in columns.items()},
                   meta=meta, n=n, ignored_columns=(), lines=np.arange(n) + 2 + len(meta),
                   segments=tuple(segments))


def run_design(design: dict, truth: dict, noise: float, seed: int, s: float = 1.0,
               F_hat: str = "avg", z_ba: float = 0.95) -> Dataset:
    """The record a plan's design gives on ``truth`` (``Fc``, ``Fs``, ``V``, ``delta``,
    optionally ``sigma`` and ``s``) with Gaussian noise of std ``noise`` [N].

    Ramps give break-away forces (E13, F̂ and z* as given, the presliding scale ``s``
    of the record, written as its ``# s:`` line); set-points give the steady force at
    +v and −v (E2); a sine gives F along x(t) sampled at the design's rate (E6').
    """
    rng = np.random.default_rng(seed)
    p = {"sigma": 0.0, **truth}
    curve = (p["Fc"], p["Fs"], p["V"], p["delta"])
    if design["family"] == "ramps":
        k = np.asarray(design["rates"], dtype=float)
        scale = p.get("s", s)
        F = breakaway_force(k, *curve, scale, p["sigma"], F_hat, z_ba)
        return _dataset("breakaway", {"k": k, "F_ba": np.abs(F + noise * rng.standard_normal(k.size))},
                        {"s": repr(float(scale))})
    if design["family"] == "steady":
        speeds = np.asarray(design["speeds"], dtype=float)
        v = np.concatenate([speeds, -speeds])
        F = steady_state_force(v, *curve, p["sigma"])
        return _dataset("steady", {"v": v, "F": F + noise * rng.standard_normal(v.size)})
    A, f = design["amplitude"], design["frequency"]
    t = np.arange(0.0, design["duration"], 1.0 / design["sample_rate"])
    x = A * np.sin(2 * np.pi * f * t)
    F = presliding_force(t, x, *curve, p["s"], p["sigma"])
    return _dataset("timeseries", {"t": t, "x": x, "F": F + noise * rng.standard_normal(t.size)})


def join(first: Dataset, second: Dataset) -> Dataset:
    """Two records of one kind as one: rows one after the other; time series as
    independent segments (each starts from its own state and time)."""
    if first.kind != second.kind:
        raise ValueError(f"cannot join a {first.kind} record to a {second.kind} record")
    names = [c for c in first.columns if c in second.columns]
    columns = {c: np.concatenate([first.columns[c], second.columns[c]]) for c in names}
    segments = ()
    if first.kind == "timeseries":
        # the second record's clock starts after the first's, so t keeps increasing
        shift = first.columns["t"][-1] - second.columns["t"][0] + \
            float(np.median(np.diff(first.columns["t"])))
        columns["t"] = np.concatenate([first.columns["t"], second.columns["t"] + shift])
        segments = (*first.segments, first.n, *(first.n + i for i in second.segments))
    if first.kind == "breakaway" and first.meta_float("s", 1.0) != second.meta_float("s", 1.0):
        raise ValueError("the two break-away records were read with different s")
    return _dataset(first.kind, columns, first.meta, segments)




def joint_fit(records, start: dict, noise) -> dict:
    """Least squares on several records at once, of any kinds, with shared parameters:
    the refit of an earlier record and a plan's new one when their kinds differ (a
    steady curve and a sine). Each record's residual is divided by its noise, so the
    standard errors follow from the Jacobian alone.

    Parameters
    ----------
    records : sequence of Dataset
    start : dict
        Starting values of ``Fc``, ``Fs``, ``V``, ``delta`` and, when a time series is
        among the records, ``s``; a break-away record takes the shared ``s`` in place of
        the one it was read with.
    noise : sequence of float
        Standard deviation of one force of each record [N].

    Returns
    -------
    dict
        ``params``, ``stderr`` and ``determined`` (relative standard error at most one,
        no correlation above 0.99), keyed like a report's.
    """
    problems = [problem_for(record) for record in records]
    names = ["Fc", "Fs", "V", "delta"] + (["s"] if any(r.kind == "timeseries" for r in records)
                                          else [])
    log = np.array([name in ("V", "s") for name in names])

    def params(theta):
        return {name: float(np.exp(v) if lg else v) for name, v, lg in zip(names, theta, log)}

    def residual(theta):
        p = params(theta)
        parts = []
        for pb, sigma in zip(problems, noise):
            if pb.kind == "breakaway" and "s" in p:
                pb.s = p["s"]
            parts.append((pb.predict(p) - pb.measured) / sigma)
        r = np.concatenate(parts)
        return np.where(np.isfinite(r), r, 1e6)

    theta0 = np.array([np.log(start[n]) if lg else start[n] for n, lg in zip(names, log)])
    result = least_squares(residual, theta0, method="trf", x_scale="jac")
    found = params(result.x)
    cov = np.linalg.pinv(result.jac.T @ result.jac)
    stderr, determined = verdicts(cov[None], names, {n: np.array([[v]]) for n, v in found.items()})
    return {"params": found, "stderr": dict(zip(names, stderr[0].tolist())),
            "determined": dict(zip(names, determined[0].tolist()))}


__all__ = ["join", "joint_fit", "run_design"]
