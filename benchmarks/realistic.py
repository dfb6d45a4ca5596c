"""Identification on rigs it has never seen (issue 26): the rig zoo's families on seeds
never used while developing, each report checked against what it must say.

Every family of ``tests/identify/rigzoo.py`` (encoders of 10 to 16,384 counts in rad or
degrees, forces that are commands or model-based estimates, hands, heavy carriages,
drifting seals, curved gearboxes, mains hum, spikes, short records, offsets, flat
sliding levels, and their combinations) is generated on the seeds of :data:`SEEDS`,
written as the CSV a user uploads, parsed and identified as ``breakaway fit FILE``
does, and checked by the tests' own :func:`~identify.expectations.failures`. With
``--machines`` the machine-like families of issue 19 (``tests/identify/machines.py``)
run too.

Per family: right / total, the kinds of miss and how often, the seconds per fit, and the
noise floor beside the obvious alternative, a plain model-free estimate (the robust
spread of F's second differences, what one computes by hand): how often each lands
within the family's tolerance of the force channel's true noise. Below the table,
every miss by seed.

Run: .venv/bin/python benchmarks/realistic.py [-j 2] [--families NAME ...] [--seeds N]
     [--machines] [--save DIR]
The table and the notes under it go to docs/benchmarks/results/realistic.md, which the
documentation includes.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import math
import os
import re
import statistics
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

# imported as pytest imports them (package ``identify`` under tests/), so that the
# plant's numba cache, keyed by module name, serves both
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from results import Results  # noqa: E402

from breakaway.identify import identify, parse_csv  # noqa: E402
from identify.expectations import failures  # noqa: E402
from identify.machines import families as machine_families  # noqa: E402
from identify.rigzoo import families as zoo_families  # noqa: E402

#: Seeds never used while developing the engine or the zoo (the tests use 0–9).
SEEDS = tuple(range(1000, 1010))

#: Seeds to develop on: neither the tests' nor the unseen ones.
DEVELOPMENT_SEEDS = tuple(range(2000, 2010))

#: Kinds of miss: a phrase of :func:`failures`' message and its kind (first match wins).
MISS_KINDS = (
    ("named but not in the data", "named, not there"),
    (" not named (", "missed effect"),
    (" not refused as ", "not refused"),
    ("no beyond-data message", "beyond-data bound"),
    ("without a beyond-data warning", "V beyond data, unflagged"),
    ("none of the warnings", "missing warning"),
    (" warning", "missing warning"),
    ("noise floor", "noise floor"),
    ("input_floor", "no input_floor"),
    ("determined above", "determined beyond data"),
    ("determined, expected not determined", "determined, should not be"),
    ("not determined", "undetermined"),
    ("unexplained is", "unexplained flag"),
    ("residual_structure", "structure"),
    (", expected ", "value off"),
)


def miss_kind(message: str) -> str:
    """The kind of one failure message (see :data:`MISS_KINDS`)."""
    return next((kind for phrase, kind in MISS_KINDS if phrase in message), "other")


def refusal(message: str) -> str | None:
    """The reason a required effect was not named, its numbers blanked (``#``), so that
    the same rule counts once; None for other failures."""
    if " not named (" not in message:
        return None
    reason = message.split(" not named (", 1)[1][:-1]
    return re.sub(r"[-+]?\d[\d.]*(?:e[-+]?\d+)?", "#", reason)[:70]


def plain_floor(csv: str) -> float:
    """The obvious model-free noise estimate: the median absolute second difference of
    F along the file's order (steady curves: along v per direction), scaled to a
    standard deviation (1.4826/√6)."""
    data = parse_csv(csv)
    F = data.columns["F"] if "F" in data.columns else data.columns["F_ba"]
    if data.kind == "steady":
        v = data.columns["v"]
        parts = [F[np.argsort(v)][np.sort(v) < 0], F[np.argsort(v)][np.sort(v) > 0]]
    else:
        parts = [F]
    diffs = np.concatenate([np.diff(p, 2) for p in parts if p.size > 3])
    return 1.4826 * float(np.median(np.abs(diffs))) / math.sqrt(6)


def _floor_ok(value, noise) -> bool | None:
    if noise is None:
        return None
    target, factor = noise
    return target / factor <= value <= target * factor


def run_one(job):
    """Generate, identify and check one recording (in a worker process)."""
    name, seed, save = job
    make = {**zoo_families(), **machine_families()}[name]
    recording = make(seed)
    started = time.perf_counter()
    report = identify(parse_csv(recording.csv))
    seconds = time.perf_counter() - started
    if save:
        with open(os.path.join(save, f"{name}-{seed}.json"), "w") as f:
            json.dump(report, f, indent=1, default=float)
        with open(os.path.join(save, f"{name}-{seed}.csv"), "w") as f:
            f.write(recording.csv)
    noise = recording.expect.noise
    return {"family": name, "seed": seed, "failures": failures(report, recording.expect),
            "effects": report["effects"], "seconds": seconds,
            "floor_ok": _floor_ok(report["noise_floor"], noise),
            "plain_ok": _floor_ok(plain_floor(recording.csv), noise)}


def _share(flags) -> str:
    flags = [f for f in flags if f is not None]
    return f"{sum(flags)}/{len(flags)}" if flags else "-"


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-j", type=int, default=1, help="parallel fits (2 uses both cores)")
    parser.add_argument("--families", nargs="+", metavar="NAME",
                        help="only these families (shell patterns, e.g. 'hand-*')")
    parser.add_argument("--seeds", type=int, default=len(SEEDS),
                        help=f"the first N of the seeds {SEEDS[0]}–{SEEDS[-1]}")
    parser.add_argument("--skip", type=int, default=0, help="skip the first N of those seeds")
    parser.add_argument("--development", action="store_true",
                        help="the development seeds 2000– instead (printed, not written to "
                             "the documentation's results)")
    parser.add_argument("--machines", action="store_true",
                        help="also the machine-like families of issue 19")
    parser.add_argument("--save", metavar="DIR", help="write each report and CSV to DIR")
    args = parser.parse_args()

    chosen = list(zoo_families()) + (list(machine_families()) if args.machines else [])
    if args.families:
        chosen = [name for name in chosen
                  if any(fnmatch.fnmatch(name, pattern) for pattern in args.families)]
        if not chosen:
            parser.error(f"no family matches {' '.join(args.families)}")
    if args.save:
        os.makedirs(args.save, exist_ok=True)
    out = Results("realistic", __file__)
    seeds = (DEVELOPMENT_SEEDS if args.development else SEEDS)[args.skip:args.seeds]
    jobs = [(name, seed, args.save) for name in chosen for seed in seeds]
    print(f"{len(chosen)} families × seeds {seeds[0]}–{seeds[-1]} = {len(jobs)} fits, "
          f"-j {args.j}; load average before: "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    started = time.perf_counter()
    if args.j > 1:
        with ProcessPoolExecutor(args.j) as pool:
            results = list(pool.map(run_one, jobs))
    else:
        results = [run_one(job) for job in jobs]
    wall = time.perf_counter() - started

    rows, right_total = [], [0, 0]
    below_target = []
    for name in chosen:
        mine = [r for r in results if r["family"] == name]
        right = sum(not r["failures"] for r in mine)
        # input_floor is new in the report: the rest of the verdict apart
        nearly = sum(all(miss_kind(m) == "no input_floor" for m in r["failures"]) for r in mine)
        right_total[0] += right
        right_total[1] += len(mine)
        if right < 0.9 * len(mine):
            below_target.append(name)
        kinds = {}
        for r in mine:
            for kind in {miss_kind(m) for m in r["failures"]}:
                kinds[kind] = kinds.get(kind, 0) + 1
        misses = ", ".join(f"{k} × {c}" for k, c in sorted(kinds.items(), key=lambda kc: -kc[1]))
        seconds = [r["seconds"] for r in mine]
        rows.append([name, f"{right}/{len(mine)}", f"{nearly}/{len(mine)}", misses or "-",
                     f"{statistics.median(seconds):.1f}, {max(seconds):.1f}",
                     f"{_share(r['floor_ok'] for r in mine)}, "
                     f"{_share(r['plain_ok'] for r in mine)}"])
    print()
    out.note(f"**{right_total[0]} of {right_total[1]} recordings get the report they must**; "
             f"{len(chosen) - len(below_target)} of {len(chosen)} families at ≥ 90 % "
             f"(seeds {seeds[0]}–{seeds[-1]}, {wall:.0f} s wall)"
             + (f"; below 90 %: {', '.join(below_target)}." if below_target else "."))
    out.table(["family", "right", "right but for input_floor", "misses (kind × count)",
               "s per fit (median, max)", "floor within tolerance: engine, plain estimate"],
              rows)
    wrong = [r for r in results if r["failures"]]
    unnamed = []
    for name in chosen:
        reasons = {}
        for r in results:
            if r["family"] == name:
                for why in filter(None, map(refusal, r["failures"])):
                    reasons[why] = reasons.get(why, 0) + 1
        if reasons:
            top = sorted(reasons.items(), key=lambda kv: -kv[1])[:3]
            unnamed.append(f"- {name}: " + "; ".join(f"{why} × {count}" for why, count in top))
    if unnamed:
        out.note("Why required effects went unnamed (the engine's reasons, numbers as #):\n\n"
                 + "\n".join(unnamed))
    if wrong:
        print("\nMisses:")
        for r in wrong:
            print(f"- {r['family']} seed {r['seed']} (effects: "
                  f"{', '.join(r['effects']) or 'none'}):")
            for message in r["failures"]:
                print(f"    {message}")
    if not args.development:
        out.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
