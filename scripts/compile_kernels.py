"""Compile the package's numba kernels into their on-disk cache, in one process.

The suite's workers would otherwise each compile what they meet first (half a minute
on a fresh clone, twice over when both workers reach the same kernels together); once
cached, every process loads them in a fraction of a second. Runs what calls them: the
dynamic models' sweeps, ramps and loops, one identification of a short record read
through an encoder at uneven times, and a plan of a sine.
"""

from dataclasses import replace

import numpy as np

from breakaway.api.simulation import load_models, run_ramp, run_simulation
from breakaway.identify import identify
from breakaway.identify.synthetic import make_dataset
from breakaway.plan import plan_experiment
from breakaway.params import DEFAULTS, LUGRE_1995

PRESLIDING = {n: DEFAULTS[n] for n in ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba")}

load_models()  # the integrator and both loop models
run_simulation("lugre", [1.0], LUGRE_1995, 10_000)
run_ramp("presliding", 1.0, PRESLIDING, 10_000)
run_ramp("lugre", 1.0, LUGRE_1995, 10_000)
record = make_dataset("timeseries", ("backlash",), seed=0, n=2000)[0]
t = record.columns["t"]
read = 1e-5 * np.round(record.columns["x"] / 1e-5)  # through an encoder of 10 µm counts
jittered = t + np.random.default_rng(0).uniform(0.0, 0.2, t.size) * np.median(np.diff(t))
identify(replace(record, columns={**record.columns, "t": jittered, "x": read}))
plan_experiment("sine", params={"Fc": 2.0, "Fs": 3.0, "V": 2e-3, "delta": 2.0, "s": 5e4},
                limits={"u_max": 3.5, "v_max": 0.01, "travel": 1e-3})
