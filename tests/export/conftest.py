"""Reports and trajectories the export tests share, made by code."""

from __future__ import annotations

import numpy as np
import pytest

BASE = {"Fc": 10.0, "Fs": 15.0, "V": 5e-3, "delta": 1.5, "s": 2000.0}
LINEAR_UNITS = {"F": "N", "x": "m", "v": "m/s", "t": "s", "Fc": "N", "Fs": "N", "V": "m/s",
                "delta": "", "s": "1/m", "sigma": "N·s/m", "Fc_neg": "N", "Fs_neg": "N",
                "alpha": "1/s"}
ROTARY_UNITS = {"F": "N·m", "x": "rad", "v": "rad/s", "t": "s", "Fc": "N·m", "Fs": "N·m",
                "V": "rad/s", "delta": "", "s": "1/rad", "sigma": "N·m·s/rad", "n": ""}


def report_of(params, effects=(), kind="timeseries", t_0=2.0, units=LINEAR_UNITS):
    """A §8-shaped report around ``params`` (the keys an export reads, and a few more)."""
    params = dict(params)
    return {"kind": kind, "n": 4000, "effects": list(effects),
            "final": {"params": params, "stderr": dict.fromkeys(params, 0.0),
                      "determined": dict.fromkeys(params, True), "rmse": 0.1, "bic": 0.0},
            "units": dict(units), **({"t_0": t_0} if t_0 is not None else {})}


#: Reports covering every exported effect, one of them rotary and one with a
#: measurement effect that the export leaves out.
REPORTS = {
    "base": report_of(BASE),
    "all-body-effects": report_of({**BASE, "sigma": 150.0, "Fc_neg": 8.0, "Fs_neg": 10.5,
                                   "alpha": 0.05, "F_offset": 0.3},
                                  ("asymmetry", "drift", "viscous", "offset")),
    "viscous-power-rotary": report_of({**BASE, "sigma": 4e3, "n": 2.0, "delta": -0.7},
                                      ("viscous-power",), units=ROTARY_UNITS),
}


def trajectory(seed: int, n: int = 4000):
    """Sampled (t, x) with reversals big and small, rests (zero increments) and uneven
    sampling, from t = 2 s: gross sliding (±2 mm against a 0.5-mm presliding distance),
    minor loops inside presliding, and speeds from rest to 4·V."""
    rng = np.random.default_rng(seed)
    t = 2.0 + np.cumsum(rng.uniform(0.5e-3, 1.5e-3, n))
    phase = 2 * np.pi * (t - t[0])
    x = (2e-3 * np.sin(0.35 * phase + rng.uniform(0, 2 * np.pi))
         + 1.5e-4 * np.sin(3.1 * phase) + 2e-5 * rng.standard_normal(n).cumsum() / 30)
    step = np.diff(x)
    for start in rng.choice(n - 60, 6, replace=False):  # rests: the position held
        step[start:start + 40] = 0.0
    return t, np.concatenate(([x[0]], x[0] + np.cumsum(step)))


@pytest.fixture(params=sorted(REPORTS))
def report(request):
    return REPORTS[request.param]
