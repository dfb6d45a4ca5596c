"""Speed and honesty of the plan of the next experiment.

    .venv/bin/python benchmarks/bench_plan.py [--quick]

1. A plan at the default limits, each family, for three starting points: break-away
   ramps at high rates only (V, δ and Fs wholly open: 45 draws), a steady curve that
   holds V loosely, and the explorer's default parameters (one draw).
2. The search against the brute force: the ramps plan of case 1 on a coarser grid of
   rates and fewer runs, where every design can be scored (all multisets of the
   grid), and how long the brute force would take at the default grid and runs.
3. The simulated checks (``breakaway.plan.checks``) over many seeds: how often the
   actual errors after the plan fall within two standard errors — those the refit
   gives when V and δ were wholly open, those the plan predicted when the first record
   held V (or s) loosely. About 95 % is right; 88 to 99 % is the band the tests of the
   few-seed versions keep to.

Timings are medians of repeated in-process calls after a warm-up (numba loads its
on-disk cache on the first call). Nothing here is asserted.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import time

import numpy as np

from breakaway.plan import plan_experiment
from breakaway.plan.checks import (coverage, loose_ramps, loose_steady, open_drop,
                                   sine_for_s)
from breakaway.plan.planner import FAMILIES, _knowledge, _outcome
from breakaway.plan.search import choose_runs, criterion, exhaustive


def median_time(func, repeat=5):
    func()
    times = []
    for _ in range(repeat):
        started = time.perf_counter()
        func()
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def plan_times(repeat):
    print("1. one plan at the default limits (median of", repeat, "calls)")
    high = open_drop(1).report
    steady = loose_steady(0).report
    starts = {"ramps at high rates (report)": dict(report=high, limits={"u_max": 3.0}),
              "steady curve from V (report)": dict(report=steady, limits={"u_max": 20.0}),
              "explorer defaults (params)": dict(params={})}
    for label, source in starts.items():
        row = []
        for family in FAMILIES:
            kwargs = dict(source)
            if family != "steady" and kwargs.get("report", {}).get("kind") == "steady":
                kwargs["ranges"] = {"s": (500.0, 8000.0)}  # a steady curve holds no s
            seconds = median_time(lambda: plan_experiment(family, **kwargs), repeat)
            row.append(f"{family} {1000 * seconds:6.0f} ms")
        print(f"   {label:32s}", " | ".join(row))


def against_brute_force(grid, runs):
    print(f"\n2. the search against the brute force: ramps at high rates, {runs} runs on "
          f"{grid} rates, 45 draws")
    knowledge = _knowledge(open_drop(1).report, None, None)
    outcome = _outcome(knowledge, FAMILIES["ramps"], {"u_max": 3.0}, runs, None, None, grid)
    rows, known = outcome.information.rows, outcome.known
    targets = [outcome.names.index(name) for name in outcome.targets]
    started = time.perf_counter()
    counts = choose_runs(known, rows, runs, targets)
    search_seconds = time.perf_counter() - started
    found = criterion(known + np.einsum("g,qgi,qgj->qij", counts, rows, rows), targets)
    started = time.perf_counter()
    _, best, scored = exhaustive(known, rows, runs, targets)
    brute_seconds = time.perf_counter() - started
    print(f"   search: {1000 * search_seconds:8.1f} ms, criterion {found:.4f}")
    print(f"   brute force: {brute_seconds:8.1f} s over {scored} designs, best {best:.4f} "
          f"(search − best: {found - best:+.2e})")
    designs = math.comb(96 + 12 - 1, 12)
    years = designs * brute_seconds / scored / (365.25 * 86400)
    print(f"   at the default 96 rates and 12 runs the brute force would score {designs:.3g} "
          f"designs: {years:.2g} years at this rate")


def checks(seeds):
    print(f"\n3. simulated checks over {seeds} seeds: actual errors within two standard errors")
    cases = [("V, δ wholly open (ramps at high rates), the refit's own", open_drop,
              ("Fs", "V", "delta"), "refit"),
             ("V loose from ramps across part of the drop, predicted", loose_ramps, ("V",),
              "predicted"),
             ("V loose from a steady curve with no speed below V, predicted", loose_steady,
              ("V",), "predicted"),
             ("s from a sine, after a steady curve, predicted", sine_for_s, ("s",), "predicted")]
    for label, case, names, against in cases:
        started = time.perf_counter()
        done = [case(seed) for seed in range(seeds)]
        parts = []
        for name in names:
            hits, counted = coverage(done, name, against)
            parts.append(f"{name} {hits}/{counted} = {100 * hits / max(counted, 1):.0f} %")
        determined = sum(all(c.refit["determined"].get(n, False) for n in names) for c in done)
        print(f"   {label}: {', '.join(parts)}; refit determines them in {determined}/{seeds} "
              f"({time.perf_counter() - started:.0f} s)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer seeds, a smaller brute force")
    args = parser.parse_args()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} (other work on the "
          "machine slows every figure alike)\n")
    plan_times(3 if args.quick else 7)
    if args.quick:
        against_brute_force(16, 3)
    else:
        against_brute_force(24, 4)
    checks(12 if args.quick else 60)


if __name__ == "__main__":
    main()
