"""Speed of the position loop (PID on m·ẍ + F = u) against scipy's solve_ivp on the same loop.

    .venv/bin/python benchmarks/bench_loop.py [--quick]

1. The loop view's default run (presliding, params.LOOP_DEFAULTS: a 5-s step that
   hunts, 2000 output points): ``simulate_loop`` and the whole ``loop_experiment``
   (stick phases, E13, hunting), against ``solve_ivp`` RK45 and DOP853 on the same
   loop with an event per reversal and a restart in Python (the obvious alternative),
   each at the same rtol; the error of x against DOP853 at rtol 1e-10.
2. The LuGre default loop (5 s, 2000 points): ``simulate_loop`` against ``solve_ivp``
   Radau and LSODA at the same rtol (LuGre's bristle is stiff in sliding, so explicit
   RK45 is no alternative), the error of x against Radau at rtol 1e-10.

Timings are medians of repeated in-process calls after a warm-up (numba loads its
cache on the first call); the load average is printed beside them. Nothing is asserted.
The table goes to docs/benchmarks/results/loop.md, which the documentation includes.
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results import Results, load_average, machine  # noqa: E402

from breakaway.dynamics import DEFAULT_RTOL, simulate_loop  # noqa: E402
from breakaway.loop import loop_experiment  # noqa: E402
from breakaway.params import DEFAULTS, LOOP_DEFAULTS, LUGRE_1995  # noqa: E402

DURATION, POINTS = 5.0, 2000
PLANT = {**{k: DEFAULTS[k] for k in ("Fc", "Fs", "V", "delta", "sigma", "s", "z_ba")},
         "m": LOOP_DEFAULTS["presliding"]["m"]}


def gains(model):
    return {name: LOOP_DEFAULTS[model][name] for name in ("Kp", "Ki", "Kd", "u_max")}


def median_time(func, repeat):
    func()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times)


def g(v, Fc, Fs, V, delta):
    if v == 0:
        return Fs if delta > 0 else Fc
    return Fc + (Fs - Fc) * math.exp(-((abs(v) / V) ** delta))


def presliding_ivp(t_eval, rtol, method):
    """x on t_eval of (E6') under the default PID and step, solve_ivp restarted at each
    reversal (the memory x_r, F_r, d switched in Python)."""
    P, c, h = PLANT, gains("presliding"), LOOP_DEFAULTS["presliding"]["h"]
    mem = {"x_r": 0.0, "F_r": 0.0, "d": 1.0}

    def force(x, v):
        z = min(P["s"] * abs(x - mem["x_r"]), 1.0)
        shape = z * (1 - math.log(z)) if z > 0 else 0.0
        return mem["F_r"] + (mem["d"] * g(v, P["Fc"], P["Fs"], P["V"], P["delta"])
                             + P["sigma"] * v - mem["F_r"]) * shape

    def rhs(t, y):
        return [y[1], (c["Kp"] * (h - y[0]) + c["Ki"] * y[2] - c["Kd"] * y[1]
                       - force(y[0], y[1])) / P["m"], h - y[0]]

    def reversal(t, y):
        return y[1] * mem["d"]

    reversal.terminal, reversal.direction = True, -1
    x = np.full(t_eval.size, np.nan)
    t0, y0 = 0.0, [0.0, 0.0, 0.0]
    while True:
        sol = solve_ivp(rhs, (t0, t_eval[-1]), y0, method=method, rtol=rtol,
                        atol=1e-3 * rtol / P["s"], events=[reversal], dense_output=True)
        inside = (t_eval >= t0) & (t_eval <= sol.t[-1])
        if np.any(inside):
            x[inside] = sol.sol(t_eval[inside])[0]
        if sol.status == 0:
            return x
        t0, y = sol.t_events[0][0], sol.y_events[0][0]
        mem["F_r"] = force(y[0], y[1])
        mem["x_r"], mem["d"] = y[0], -mem["d"]
        y0 = [y[0], 0.0, y[2]]


def lugre_ivp(t_eval, rtol, method):
    """x on t_eval of LuGre under the default PID and step."""
    q, c, h = LUGRE_1995, gains("lugre"), LOOP_DEFAULTS["lugre"]["h"]

    def rhs(t, y):
        x, v, z, integral = y
        z_dot = v - q["sigma0"] * abs(v) * z / g(v, q["Fc"], q["Fs"], q["vs"], q["delta"])
        F = q["sigma0"] * z + q["sigma1"] * z_dot + q["sigma2"] * v
        u = c["Kp"] * (h - x) + c["Ki"] * integral - c["Kd"] * v
        return [v, (u - F) / q["m"], z_dot, h - x]

    bristle = q["Fs"] / q["sigma0"]
    atol = 1e-3 * rtol * np.array([bristle, bristle * math.sqrt(q["sigma0"] / q["m"]), bristle,
                                   q["Fs"] / c["Ki"]])
    sol = solve_ivp(rhs, (0.0, t_eval[-1]), [0.0] * 4, method=method, rtol=rtol, atol=atol,
                    t_eval=t_eval)
    return sol.y[0]


def report(name, t_run, t_min, extra=""):
    print(f"   {name:38s} median {t_run * 1e3:8.1f} ms (min {t_min * 1e3:.1f}){extra}")


def bench(model, quick):
    rtol = DEFAULT_RTOL
    h = LOOP_DEFAULTS[model]["h"]
    plant = PLANT if model == "presliding" else {"z_ba": DEFAULTS["z_ba"]}
    step = {"kind": "step", "h": h}

    def compiled():
        return simulate_loop(plant, gains(model), step, DURATION, model=model, points=POINTS)

    run = compiled()
    grid = run.code == 0
    t = run.t[grid]
    alternatives = (("RK45", "DOP853") if model == "presliding" else ("Radau", "LSODA"))
    reference_method = "DOP853" if model == "presliding" else "Radau"
    solve = presliding_ivp if model == "presliding" else lugre_ivp
    x_ref = solve(t, 1e-10, reference_method)
    repeat = 5 if quick else 30
    print(f"{1 if model == 'presliding' else 2}. {model}: default loop, {DURATION:g} s, "
          f"{POINTS} points, rtol {rtol:g} ({run.reversals} reversals, "
          f"{np.count_nonzero(run.code & 2)} break-aways)")
    t_run, t_min = median_time(compiled, repeat)
    err = np.max(np.abs(run.x[grid] - x_ref)) / h
    report("simulate_loop (compiled DP5)", t_run, t_min,
           f"; max |x − x_ref| = {err:.1e}·h")
    t_all, t_all_min = median_time(lambda: loop_experiment(
        model, plant, gains(model), step, DURATION, points=POINTS), repeat)
    report("loop_experiment (+ phases, E13, hunting)", t_all, t_all_min)
    out = {"ms": t_run * 1e3, "min_ms": t_min * 1e3, "all_ms": t_all * 1e3, "err": err,
           "reversals": run.reversals, "breakaways": np.count_nonzero(run.code & 2),
           "reference": reference_method, "alternatives": []}
    for method in alternatives:
        t0 = time.perf_counter()
        x = solve(t, rtol, method)
        t_sp = time.perf_counter() - t0
        e = np.max(np.abs(x - x_ref)) / h
        between = np.max(np.abs(x - run.x[grid])) / h
        print(f"   solve_ivp {method:6s} rtol {rtol:g}{'':17s} {t_sp * 1e3:8.1f} ms -> "
              f"{t_sp / t_run:.0f}x slower; max |x − x_ref| = {e:.1e}·h, "
              f"vs compiled {between:.1e}·h")
        out["alternatives"].append((method, t_sp * 1e3, e))
    print(f"   (x_ref: solve_ivp {reference_method} at rtol 1e-10)")
    return out


def row(name, r):
    """One loop's row of the table the docs include."""
    against = "; ".join(f"{method} {ms:.0f} ms ({ms / r['ms']:.0f}×)"
                        for method, ms, _ in r["alternatives"])
    errors = "; ".join([f"compiled {r['err']:.1e}·h"] + [f"{method} {e:.1e}·h" for method, _, e
                                                          in r["alternatives"]])
    return [f"{name} ({r['reversals']} reversals, {r['breakaways']} break-aways)",
            f"{r['ms']:.1f} ms (min {r['min_ms']:.1f})", f"{r['all_ms']:.1f} ms",
            against, f"{errors} (reference: {r['reference']} at rtol 1e-10)"]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    args = parser.parse_args(argv)
    out = Results("loop", __file__)
    print(f"Machine: {machine()}")
    print(f"Load average (1, 5, 15 min) at start: {load_average()}")
    print()
    presliding = bench("presliding", args.quick)
    print()
    lugre = bench("lugre", args.quick)
    print()
    out.table(["loop", "compiled `simulate_loop`", "+ phases, E13, hunting",
               "solve_ivp on the same loop, same rtol", "error of x vs a tight reference"],
              [row("presliding default", presliding), row("LuGre default", lugre)])
    out.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
