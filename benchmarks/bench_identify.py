"""Identification speed: parsing and the full fit + diagnosis per data kind.

Prints each figure next to the obvious alternative measured in the same run:
numpy.genfromtxt for parsing, scipy.signal.lombscargle for the residual's periodogram
against x (the ripple's starts and the short-travel check), and the same diagnosis with
BLAS left multi-threaded (what you get without threadpoolctl).

Run: .venv/bin/python benchmarks/bench_identify.py [--against REV]
With ``--against REV`` (default: the engine at the start of this round's identification
work) a 10,000-row record is also fitted by that revision's engine, checked out into a
temporary git worktree and run in a subprocess on the same file in the same run: the
engine may take at most twice that time.
The table goes to docs/benchmarks/results/identify.md, which the documentation includes.
"""

from __future__ import annotations

import argparse
import io
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.signal import lombscargle
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))
ROOT = Path(__file__).resolve().parents[1]
from results import Results, machine  # noqa: E402

from breakaway.identify import diagnose, parse_csv  # noqa: E402
from breakaway.identify import diagnosis as diagnosis_module  # noqa: E402
from breakaway.identify.effects import periodogram  # noqa: E402
from breakaway.identify.synthetic import make_dataset, to_csv  # noqa: E402


def _time(fn, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


#: The engine before the selection of held-out blocks (issue 26's start).
BASELINE_REV = "94dd059"
#: The fit whose time is compared with the baseline's.
COMPARED_ROWS = 10_000
_TIMED_FIT = """
import statistics, sys, time
sys.path.insert(0, sys.argv[1])
from breakaway.identify import diagnose, parse_csv
text = open(sys.argv[2], "rb").read()
times = []
for _ in range(3):
    t0 = time.perf_counter()
    diagnose(parse_csv(text))
    times.append(time.perf_counter() - t0)
print(statistics.median(times))
"""


def timed_fit(backend: Path, csv: Path) -> float:
    """Median seconds of three fits + diagnoses of ``csv`` by the engine in ``backend``
    (a fresh interpreter: nothing of the other engine is imported)."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(csv.parent / f"numba-{backend.parent.name}")}
    done = subprocess.run([sys.executable, "-c", _TIMED_FIT, str(backend), str(csv)],
                          capture_output=True, text=True, env=env, check=True)
    return float(done.stdout.strip().splitlines()[-1])


def against(rev: str) -> tuple[float, float, int]:
    """This engine's and ``rev``'s times on the same 10,000-row record [s], and its rows."""
    data, _ = make_dataset("timeseries", ("viscous", "asymmetry"), seed=1, n=COMPARED_ROWS)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        csv = tmp / "record.csv"
        csv.write_text(to_csv(data))
        old = tmp / "baseline"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", "-q", str(old),
                        rev], check=True)
        try:
            for backend in (old / "backend", ROOT / "backend"):
                timed_fit(backend, csv)  # each engine's compiled functions cached once
            theirs = timed_fit(old / "backend", csv)
            ours = timed_fit(ROOT / "backend", csv)
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(old)],
                           check=False)
    return ours, theirs, data.n


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--against", default=BASELINE_REV, metavar="REV",
                        help="git revision whose engine the 10,000-row fit is compared with "
                             "('' to skip)")
    args = parser.parse_args(argv)
    out = Results("identify", __file__)
    print(f"machine: {machine()}")
    data, _ = make_dataset("timeseries", (), seed=0, n=20_000)
    text = to_csv(data).encode()
    ours = _time(lambda: parse_csv(text), repeat=5)
    theirs = _time(lambda: np.genfromtxt(io.BytesIO(text), delimiter=",", names=True), repeat=5)
    print(f"parse 20,000-row CSV: {ours * 1e3:.1f} ms (numpy.genfromtxt: {theirs * 1e3:.1f} ms, "
          f"{theirs / ours:.1f}x slower)")

    # the periodogram as the ripple takes it: 4,000 rows (a longer record is thinned to
    # them) at 600 wavelengths
    rng = np.random.default_rng(0)
    x = np.cumsum(rng.uniform(-1.0, 1.0, 4000)) * 1e-4
    r = np.sin(2 * np.pi * x / 3e-3) + rng.standard_normal(x.size)
    wavelengths = np.geomspace(1e-4, 1e-2, 600)
    periodogram(x, r, wavelengths)  # numba compiles or loads its cache
    compiled = _time(lambda: periodogram(x, r, wavelengths), repeat=5)
    dense = _time(lambda: lombscargle(x, r - r.mean(), 2 * np.pi / wavelengths), repeat=5)
    print(f"periodogram, 4,000 rows x 600 wavelengths: {compiled * 1e3:.1f} ms "
          f"(scipy.signal.lombscargle: {dense * 1e3:.1f} ms, {dense / compiled:.1f}x slower)")

    cases = [("timeseries", (), 20_000), ("timeseries", ("backlash",), 20_000),
             ("timeseries", ("viscous", "asymmetry"), 20_000),
             ("steady", ("viscous",), None), ("breakaway", ("dwell",), None)]
    print("\nfit + full diagnosis (median of 3; budget: timeseries 20k <= 10 s, others <= 1 s)")
    print(f"{'kind':<11} {'effects in the data':<22} {'rows':>6} {'time':>8} "
          f"{'threaded BLAS':>14}  found")
    rows = []
    for kind, effects, n in cases:
        data, _ = make_dataset(kind, effects, seed=1, n=n)
        found = diagnose(data).effects
        pinned = _time(lambda: diagnose(data))
        # the alternative: the same work with BLAS free to use every core
        original = diagnosis_module.threadpool_limits
        diagnosis_module.threadpool_limits = lambda **_: threadpool_limits(limits=None)
        try:
            threaded = _time(lambda: diagnose(data), repeat=1)
        finally:
            diagnosis_module.threadpool_limits = original
        print(f"{kind:<11} {', '.join(effects) or '-':<22} {data.n:>6} {pinned:>7.2f}s "
              f"{threaded:>13.2f}s  {', '.join(found) or '-'}")
        rows.append([kind, ", ".join(effects) or "base model only", f"{data.n:,}",
                     f"{pinned:.2f} s", f"{threaded:.2f} s", ", ".join(found) or "none"])
    print()
    out.table(["data", "effects in the data", "rows", "fit + full diagnosis (median of 3)",
               "with threaded BLAS (one run)", "effects found"], rows)
    out.note(f"A 20,000-row CSV parses in {ours * 1e3:.1f} ms (`numpy.genfromtxt`: "
             f"{theirs * 1e3:.1f} ms).")
    out.note(f"The residual's periodogram against x (4,000 rows, 600 wavelengths) takes "
             f"{compiled * 1e3:.1f} ms (`scipy.signal.lombscargle`: {dense * 1e3:.1f} ms).")
    if args.against:
        now, before, n = against(args.against)
        verdict = "within" if now <= 2 * before else "MORE than"
        out.note(f"A {n:,}-row record (viscous friction and an asymmetry) fits and is "
                 f"diagnosed in {now:.2f} s; the engine of revision {args.against} took "
                 f"{before:.2f} s on the same file in the same run ({now / before:.2f}×, "
                 f"{verdict} the 2× allowed).")
    out.write()


if __name__ == "__main__":
    main()
