"""Speed figures of the model core, each against the obvious alternative.

    .venv/bin/python benchmarks/bench_core.py [--quick]

1. One explorer frame (Stribeck 400 points, loop 2,000, phase 16 × 200, break-away
   4 × 200): ``explore_frame`` against the same frame written as plain Python loops
   (``math`` module, the self-consistent root by ``scipy.optimize.brentq``).
2. The simulated break-away over the 15 Fig. 3 rates, default preset: the compiled
   integrator against ``scipy.integrate.solve_ivp`` on the same problem (RK45, the same
   Dormand–Prince pair, the same tolerances; events for reversal and break-away, the
   integration restarted at each reversal in a Python loop). Accuracy against a converged
   reference of the same integrator (rtol 1e-12) and the chaotic band at k = 0.01.
3. The LuGre break-away (first local maximum of F) over six rates against solve_ivp
   (Radau and LSODA, event on dF/dt), accuracy against a Radau rtol 1e-10 reference.
4. E13 for the four F̂ against the simulation, default preset.

The speed table and the E13 table are written to docs/benchmarks/results/ (core_speed.md,
core_e13.md), which the documentation includes.

Timings are medians of repeated in-process calls after a warm-up (numba compiles or
loads its on-disk cache on the first call). Nothing here is asserted: the test suite
checks values, this file reports speed.
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
from scipy.optimize import brentq, minimize_scalar

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results import Results, machine  # noqa: E402

from breakaway import dynamics  # noqa: E402
from breakaway.frame import FRAME_GRID, explore_frame  # noqa: E402
from breakaway.params import DEFAULTS, FIG3_RATES, LUGRE_1995  # noqa: E402
from breakaway.presliding import LOOP_TURNING_POINTS  # noqa: E402
from breakaway.quasistatic import breakaway_force, breakaway_velocity  # noqa: E402

PRESET = {key: DEFAULTS[key] for key in ("Fc", "Fs", "V", "delta", "s", "sigma", "m", "z_ba")}
LUGRE_RATES = [0.5, 1.0, 2.0, 5.0, 10.0, 20.0]


def median_time(func, repeat, warmup=1):
    for _ in range(warmup):
        func()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        func()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), min(times)


# ---------------------------------------------------------------------------------
# 1. the explorer frame, and the same frame in plain Python
# ---------------------------------------------------------------------------------


def naive_frame(p):
    """The four plots of ``explore_frame`` with per-point Python loops."""
    Fc, Fs, V, delta, s, sigma = p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"]
    z_ba, k_now = p["z_ba"], p["k"]

    def g(v):
        if v == 0:
            return Fs if delta > 0 else Fc
        return Fc + (Fs - Fc) * math.exp(-((abs(v) / V) ** delta))

    def fss(v):
        return math.copysign(g(v), v) + sigma * v if v != 0 else 0.0

    # Stribeck curve
    n = FRAME_GRID["stribeck"]
    vs = [-5 * V + 10 * V * i / (n - 1) for i in range(n)]
    stribeck = [fss(v) for v in vs]
    # hysteresis loop: the same half-cosine excitation, then (E6') sample by sample
    n = FRAME_GRID["loop"]
    pts = [tp * 1.5 / s for tp in LOOP_TURNING_POINTS]
    speed = 0.1 * V
    dur = [math.pi / 2 * abs(b - a) / speed or 1.0 for a, b in zip(pts, pts[1:])]
    start = [0.0]
    for d_ in dur:
        start.append(start[-1] + d_)
    xs, ts = [], []
    for i in range(n):
        phase = (len(pts) - 1) * i / (n - 1)
        seg = min(int(phase), len(pts) - 2)
        frac = phase - seg
        a, b = pts[seg], pts[seg + 1]
        xs.append(a + (b - a) * 0.5 * (1 - math.cos(math.pi * frac)))
        ts.append(start[seg] + frac * dur[seg] + i * 1e-12)
    vel = [(xs[1] - xs[0]) / (ts[1] - ts[0])]
    for i in range(1, n - 1):  # numpy.gradient's second-order formula for uneven steps
        h0, h1 = ts[i] - ts[i - 1], ts[i + 1] - ts[i]
        vel.append((h0 * h0 * xs[i + 1] - h1 * h1 * xs[i - 1] + (h1 * h1 - h0 * h0) * xs[i])
                   / (h0 * h1 * (h0 + h1)))
    vel.append((xs[-1] - xs[-2]) / (ts[-1] - ts[-2]))
    d_prev, x_r, F_r, loop = None, xs[0], 0.0, []
    first = next((math.copysign(1.0, b - a) for a, b in zip(xs, xs[1:]) if b != a), 1.0)
    for i in range(n):
        d = first if i == 0 else (math.copysign(1.0, xs[i] - xs[i - 1])
                                  if xs[i] != xs[i - 1] else d_prev)
        if i > 0 and d != d_prev:
            x_r, F_r = xs[i - 1], loop[-1]
        z = min(s * abs(xs[i] - x_r), 1.0)
        shape = z * (1 - math.log(z)) if z > 0 else 0.0
        loop.append(F_r + (d * g(vel[i]) + sigma * vel[i] - F_r) * shape)
        d_prev = d
    # phase family (E12), F̂ = avg
    n = FRAME_GRID["phase"]
    f_hat = Fc + (Fs - Fc) / 2
    zs = [0.99 * i / (n - 1) for i in range(n)]
    phase = [[k / (s * f_hat * -math.log(z)) if z > 0 else 0.0 for z in zs]
             for k in list(FIG3_RATES) + [k_now]]
    # break-away curves (E13); 'self' by brentq on ẋ·Fss(ẋ) = c (monotone here)
    n = FRAME_GRID["breakaway"]
    ks = [0.01 + (30.0 - 0.01) * i / (n - 1) for i in range(n)]
    curves = {}
    for name, lvl in (("Fc", Fc), ("Fs", Fs), ("avg", f_hat)):
        curves[name] = [fss(k / (s * lvl * -math.log(z_ba))) for k in ks]
    self_curve = []
    for k in ks:
        c = k / (s * -math.log(z_ba))
        v = brentq(lambda u: u * fss(u) - c, c / max(Fc, Fs) * (1 - 1e-12),
                   c / min(Fc, Fs) * (1 + 1e-12), xtol=1e-14, rtol=1e-14)
        self_curve.append(fss(v))
    curves["self"] = self_curve
    return {"stribeck": stribeck, "hysteresis": loop, "phase": phase, "breakaway": curves}


def bench_frame(quick):
    p = dict(DEFAULTS)
    fast = explore_frame(p)
    slow = naive_frame(p)
    diff = max(
        np.max(np.abs(fast["stribeck"]["F"] - slow["stribeck"])),
        np.max(np.abs(fast["hysteresis"]["F"] - slow["hysteresis"])),
        max(np.max(np.abs(c["v"] - row) / np.maximum(1.0, np.abs(row)))
            for c, row in zip(fast["phase"]["curves"], slow["phase"])),
        max(np.max(np.abs(fast["breakaway"][name] - slow["breakaway"][name]))
            for name in ("Fc", "Fs", "avg", "self")),
    )
    t_fast, t_fast_min = median_time(lambda: explore_frame(p), 100 if quick else 500, warmup=5)
    t_slow, _ = median_time(lambda: naive_frame(p), 5 if quick else 20)
    print("1. Explorer frame (Stribeck 400, loop 2000, phase 16 x 200, break-away 4 x 200)")
    print(f"   explore_frame        median {t_fast * 1e3:7.3f} ms (min {t_fast_min * 1e3:.3f})")
    print(f"   plain-Python loops   median {t_slow * 1e3:7.3f} ms   -> {t_slow / t_fast:.0f}x")
    print(f"   same numbers: max |difference| {diff:.1e}")
    return {"frame_ms": t_fast * 1e3, "frame_min_ms": t_fast_min * 1e3,
            "naive_ms": t_slow * 1e3, "diff": diff}


# ---------------------------------------------------------------------------------
# 2. the 15-rate ramp sweep, and the same with solve_ivp
# ---------------------------------------------------------------------------------


def scipy_ramp(k, Fc, Fs, V, delta, s, sigma, m, z_ba, rtol, method="RK45"):
    """(E7) with (E6') by solve_ivp; a reversal ends the solve, the loop restarts it."""
    mem = [0.0, 0.0, 1.0]  # x_r, F_r, d

    def g(v):
        if v == 0:
            return Fs if delta > 0 else Fc
        return Fc + (Fs - Fc) * math.exp(-((abs(v) / V) ** delta))

    def force(x, v):
        z = min(s * abs(x - mem[0]), 1.0)
        shape = z * (1 - math.log(z)) if z > 0 else 0.0
        return mem[1] + (mem[2] * g(v) + sigma * v - mem[1]) * shape

    def rhs(t, y):
        return [y[1], (k * t - force(y[0], y[1])) / m]

    def reversal(t, y):
        return y[1] * mem[2]

    def breakaway(t, y):
        return s * abs(y[0] - mem[0]) - z_ba if mem[2] > 0 else -1.0

    reversal.terminal, reversal.direction = True, -1
    breakaway.terminal, breakaway.direction = True, 1
    # the same time limit, absolute tolerances and largest step as breakaway.dynamics
    t_end = 20.0 * (max(Fs, Fc) / k + (6.0 * m / (s * k)) ** (1 / 3))
    atol = [1e-3 * rtol / s, 1e-3 * rtol * k / (s * Fc)]
    t0, y0, reversals = 0.0, [0.0, 0.0], 0
    while True:
        sol = solve_ivp(rhs, (t0, t_end), y0, method=method, rtol=rtol, atol=atol,
                        max_step=t_end * 1e-3, events=[reversal, breakaway])
        if sol.status != 1:
            return math.nan, math.nan, reversals
        if sol.t_events[1].size:
            return k * sol.t_events[1][0], force(*sol.y_events[1][0]), reversals
        t0, y = sol.t_events[0][0], sol.y_events[0][0]
        mem[1] = force(*y)
        mem[0], mem[2] = y[0], -mem[2]
        y0, reversals = [y[0], 0.0], reversals + 1


def bench_sweep(quick):
    ks = np.asarray(FIG3_RATES)
    rtol = dynamics.DEFAULT_RTOL
    t0 = time.perf_counter()
    dynamics.simulate_breakaway(ks, **PRESET)
    first = time.perf_counter() - t0
    t_run, t_min = median_time(lambda: dynamics.simulate_breakaway(ks, **PRESET), 5 if quick else 15)
    t_loose, _ = median_time(lambda: dynamics.simulate_breakaway(ks, **PRESET, rtol=1e-5),
                             3 if quick else 10)
    r = dynamics.simulate_breakaway(ks, **PRESET)
    loose = dynamics.simulate_breakaway(ks, **PRESET, rtol=1e-5)
    ref = dynamics.simulate_breakaway(ks, **PRESET, rtol=1e-12)
    err = np.abs(r.u_ba / ref.u_ba - 1)
    err_loose = np.abs(loose.u_ba / ref.u_ba - 1)
    # the chaotic band at k = 0.01: the spread over tolerances
    band_rtols = (1e-6, 1e-8, 1e-10, 1e-12) if quick else (1e-6, 1e-7, 1e-8, 1e-9, 1e-10,
                                                            1e-11, 1e-12)
    band = [dynamics.simulate_breakaway(ks[:1], **PRESET, rtol=tol).u_ba[0] for tol in band_rtols]
    converged = dynamics.simulate_breakaway(ks[1:], **PRESET, rtol=1e-11).u_ba
    print()
    print("2. Ramp break-away over the 15 Fig. 3 rates, default preset "
          "(Fc=1, Fs=1.5, V=100, delta=1, m=1e-4)")
    print(f"   first call (numba compile or cache load) {first:.2f} s")
    print(f"   compiled DP5, rtol {rtol:g}   median {t_run * 1e3:7.1f} ms (min {t_min * 1e3:.1f}); "
          f"max rel. error vs rtol 1e-12: {err.max():.1e} "
          f"(k >= 2.01: {err[1:].max():.1e})")
    print(f"   compiled DP5, rtol 1e-05   median {t_loose * 1e3:7.1f} ms; "
          f"max rel. error {err_loose.max():.1e} (k >= 2.01: {err_loose[1:].max():.1e})")
    print(f"   chaotic band k=0.01: u_ba over rtol {band_rtols[0]:g}..{band_rtols[-1]:g} spans "
          f"{min(band):.5f}..{max(band):.5f} N ({max(band) / min(band) - 1:.2%}); "
          f"k >= 2.01 rtol 1e-11 vs 1e-12: {np.max(np.abs(converged / ref.u_ba[1:] - 1)):.1e}")
    t0 = time.perf_counter()
    sp = [scipy_ramp(k, **PRESET, rtol=rtol) for k in ks]
    t_scipy = time.perf_counter() - t0
    sp_u = np.array([row[0] for row in sp])
    sp_rev = [row[2] for row in sp]
    err_sp = np.abs(sp_u / ref.u_ba - 1)
    print(f"   solve_ivp RK45 + events, rtol {rtol:g}: {t_scipy * 1e3:7.0f} ms (one run) "
          f"-> {t_scipy / t_run:.0f}x slower; max rel. error {err_sp.max():.1e} "
          f"(k >= 2.01: {err_sp[1:].max():.1e}); reversals {sp_rev[:3]} vs "
          f"{[int(n) for n in r.reversals[:3]]}")
    return {"sweep_ms": t_run * 1e3, "sweep_min_ms": t_min * 1e3, "sweep_err": err.max(),
            "sweep_err_fast": err[1:].max(), "sweep_loose_ms": t_loose * 1e3,
            "sweep_loose_err": err_loose.max(), "sweep_loose_err_fast": err_loose[1:].max(),
            "scipy_ms": t_scipy * 1e3, "band": (min(band), max(band))}


# ---------------------------------------------------------------------------------
# 3. LuGre over six rates, and solve_ivp
# ---------------------------------------------------------------------------------


def lugre_parts(y, q=LUGRE_1995):
    v, z = y[1], y[2]
    gv = q["Fc"] + (q["Fs"] - q["Fc"]) * np.exp(-np.abs(v / q["vs"]) ** q["delta"])
    zdot = v - q["sigma0"] * np.abs(v) * z / gv
    return gv, zdot, q["sigma0"] * z + q["sigma1"] * zdot + q["sigma2"] * v


def scipy_lugre(k, rtol, method, q=LUGRE_1995):
    """First local maximum of F by solve_ivp with a terminal event on dF/dt (+ → −)."""
    s0, s1, s2, m = q["sigma0"], q["sigma1"], q["sigma2"], q["m"]
    dFs = q["Fs"] - q["Fc"]

    def rhs(t, y):
        v, z = y[1], y[2]
        gv = q["Fc"] + dFs * math.exp(-abs(v / q["vs"]) ** q["delta"])
        zdot = v - s0 * abs(v) * z / gv
        return [v, (k * t - s0 * z - s1 * zdot - s2 * v) / m, zdot]

    def dF_dt(t, y):
        v, z = y[1], y[2]
        r = abs(v / q["vs"]) ** q["delta"]
        gv = q["Fc"] + dFs * math.exp(-r)
        zdot = v - s0 * abs(v) * z / gv
        a = (k * t - s0 * z - s1 * zdot - s2 * v) / m
        dg = -dFs * q["delta"] * r / abs(v) * math.exp(-r) if v != 0 else 0.0  # dg/d|v|
        ratio_dot = math.copysign(1.0, v) * a * (gv - abs(v) * dg) / gv**2 if v != 0 else abs(a) / gv
        zddot = a - s0 * (ratio_dot * z + abs(v) / gv * zdot)
        return s0 * zdot + s1 * zddot + s2 * a

    dF_dt.terminal, dF_dt.direction = True, -1
    bristle = q["Fs"] / s0
    v_scale = max(k * bristle / q["Fc"], q["vs"])
    atol = [1e-3 * rtol * bristle, 1e-3 * rtol * v_scale, 1e-3 * rtol * bristle]
    T = 20.0 * (q["Fs"] / k + (6.0 * m * bristle / k) ** (1 / 3))
    sol = solve_ivp(rhs, (0.0, T), [0.0, 0.0, 0.0], method=method, rtol=rtol, atol=atol,
                    events=dF_dt)
    t = sol.t_events[0][0]
    return k * t, float(lugre_parts(sol.y_events[0][0])[2])


def lugre_reference(k, q=LUGRE_1995):
    """Radau at rtol 1e-10, dense scan of the interpolant, bounded refinement."""

    def rhs(t, y):
        _, zdot, F = lugre_parts(y, q)
        return [y[1], (k * t - F) / q["m"], zdot]

    T = 3.0 * q["Fs"] / k
    sol = solve_ivp(rhs, (0.0, T), [0.0, 0.0, 0.0], method="Radau", rtol=1e-10,
                    atol=[1e-16, 1e-14, 1e-16], dense_output=True)
    t = np.linspace(0.0, T, 60_001)
    F = lugre_parts(sol.sol(t), q)[2]
    i = (np.flatnonzero((F[1:-1] > F[:-2]) & (F[1:-1] >= F[2:])) + 1)[0]
    res = minimize_scalar(lambda tt: -lugre_parts(sol.sol(tt), q)[2], bounds=(t[i - 1], t[i + 1]),
                          method="bounded", options={"xatol": 1e-12 * T})
    return k * res.x, -res.fun


def bench_lugre(quick):
    ks = np.asarray(LUGRE_RATES)
    rtol = dynamics.DEFAULT_RTOL
    t_run, t_min = median_time(lambda: dynamics.simulate_lugre_breakaway(ks), 20 if quick else 200,
                               warmup=2)
    r = dynamics.simulate_lugre_breakaway(ks)
    ref = np.array([lugre_reference(k)[1] for k in ks])
    err = np.max(np.abs(r.F_ba / ref - 1))
    print()
    print(f"3. LuGre break-away (first local max of F), rates {LUGRE_RATES} N/s")
    print(f"   compiled DP5, rtol {rtol:g}   median {t_run * 1e3:7.2f} ms (min {t_min * 1e3:.2f}); "
          f"max rel. error of F_ba vs Radau rtol 1e-10: {err:.1e}")
    print(f"   F_ba = {np.array2string(r.F_ba, precision=4)} N, "
          f"u_ba = {np.array2string(r.u_ba, precision=4)} N")
    out = {"lugre_ms": t_run * 1e3, "lugre_err": err}
    for method in ("Radau", "LSODA", "RK45"):
        t0 = time.perf_counter()
        sp = [scipy_lugre(k, rtol, method) for k in ks]
        t_sp = time.perf_counter() - t0
        e = np.max(np.abs(np.array([row[1] for row in sp]) / ref - 1))
        print(f"   solve_ivp {method:5s} + event, rtol {rtol:g}: {t_sp * 1e3:7.1f} ms "
              f"-> {t_sp / t_run:.0f}x slower; max rel. error {e:.1e}")
        out[f"lugre_{method}_ms"] = t_sp * 1e3
    return out


def speed_table(frame, sweep, lugre):
    """The speed figures, each beside its alternative, as the docs show them."""
    lugre_alternatives = ", ".join(f"{m} {lugre[f'lugre_{m}_ms']:.0f} ms"
                                   for m in ("Radau", "LSODA", "RK45"))
    lugre_ratios = " / ".join(f"{lugre[f'lugre_{m}_ms'] / lugre['lugre_ms']:.0f}×"
                              for m in ("Radau", "LSODA", "RK45"))
    return [
        ["one explorer frame (Stribeck 400, loop 2,000, phase 16 × 200, break-away 4 × 200)",
         f"{frame['frame_ms']:.2f} ms",
         f"the same frame as plain Python loops, `self` root by `brentq`: "
         f"{frame['naive_ms']:.1f} ms (same numbers to {frame['diff']:.0e})",
         f"{frame['naive_ms'] / frame['frame_ms']:.0f}×"],
        [f"ramp break-away, 15 Fig. 3 rates, rtol {dynamics.DEFAULT_RTOL:g}; max error "
         f"{sweep['sweep_err']:.1e} (k ≥ 2.01: {sweep['sweep_err_fast']:.1e})",
         f"{sweep['sweep_ms']:.0f} ms (min {sweep['sweep_min_ms']:.0f})",
         f"`solve_ivp` RK45 (same Dormand–Prince pair and tolerances), events for reversal "
         f"and break-away, restart loop in Python: {sweep['scipy_ms'] / 1e3:.1f} s",
         f"{sweep['scipy_ms'] / sweep['sweep_ms']:.0f}×"],
        [f"the same sweep at rtol 1e-5; max error {sweep['sweep_loose_err']:.1e} "
         f"(k ≥ 2.01: {sweep['sweep_loose_err_fast']:.1e})",
         f"{sweep['sweep_loose_ms']:.0f} ms", "", ""],
        [f"LuGre break-away, 6 rates (0.5 … 20 N/s); error vs Radau rtol 1e-10: "
         f"{lugre['lugre_err']:.0e}", f"{lugre['lugre_ms']:.1f} ms",
         f"`solve_ivp` with an event on dF/dt at the same rtol: {lugre_alternatives}",
         lugre_ratios],
    ]


# ---------------------------------------------------------------------------------
# 4. E13 against the simulation
# ---------------------------------------------------------------------------------


def table(out):
    ks = np.asarray(FIG3_RATES)
    curve = {key: PRESET[key] for key in ("Fc", "Fs", "V", "delta", "s", "sigma")}
    e13 = {name: breakaway_force(ks, **curve, F_hat=name) for name in ("Fc", "Fs", "avg", "self")}
    v_e12 = breakaway_velocity(ks, **curve, F_hat="avg")
    r = dynamics.simulate_breakaway(ks, **PRESET)
    print()
    print("4. E13 against the simulation, default preset, default rtol")
    rows = []
    for j, k in enumerate(ks):
        tr = dynamics.simulate_trajectory(k, **PRESET)
        rows.append([f"{k:.2f}", f"{e13['Fc'][j]:.4f}", f"{e13['Fs'][j]:.4f}",
                     f"{e13['avg'][j]:.4f}", f"{e13['self'][j]:.4f}", f"{r.u_ba[j]:.4f}",
                     f"{r.F_ba[j]:.4f}", r.reversals[j], f"{tr.v[-1]:.2f}", f"{v_e12[j]:.2f}"])
    out.table(["k [N/s]", "E13 Fc", "E13 Fs", "E13 avg", "E13 self", "sim u_ba", "sim F_ba",
               "reversals", "sim ẋ_ba [m/s]", "E12 ẋ* avg [m/s]"], rows)
    out.write()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    parser.add_argument("--no-table", action="store_true", help="skip the README table")
    args = parser.parse_args(argv)
    speed, e13 = Results("core_speed", __file__), Results("core_e13", __file__)
    print(f"Machine: {machine()}")
    print()
    frame = bench_frame(args.quick)
    sweep = bench_sweep(args.quick)
    lugre = bench_lugre(args.quick)
    print()
    speed.table(["what", "time", "against", "ratio"], speed_table(frame, sweep, lugre))
    speed.write()
    if not args.no_table:
        table(e13)
    return 0


if __name__ == "__main__":
    sys.exit(main())
