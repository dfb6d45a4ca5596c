"""Identification speed: parsing and the full fit + diagnosis per data kind.

Prints each figure next to the obvious alternative measured in the same run:
numpy.genfromtxt for parsing, and the same diagnosis with BLAS left multi-threaded
(what you get without threadpoolctl).

Run: .venv/bin/python benchmarks/bench_identify.py
The table goes to docs/benchmarks/results/identify.md, which the documentation includes.
"""

from __future__ import annotations

import io
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results import Results, machine  # noqa: E402

from breakaway.identify import diagnose, parse_csv  # noqa: E402
from breakaway.identify import diagnosis as diagnosis_module  # noqa: E402
from breakaway.identify.synthetic import make_dataset, to_csv  # noqa: E402


def _time(fn, repeat=3):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    out = Results("identify", __file__)
    print(f"machine: {machine()}")
    data, _ = make_dataset("timeseries", (), seed=0, n=20_000)
    text = to_csv(data).encode()
    ours = _time(lambda: parse_csv(text), repeat=5)
    theirs = _time(lambda: np.genfromtxt(io.BytesIO(text), delimiter=",", names=True), repeat=5)
    print(f"parse 20,000-row CSV: {ours * 1e3:.1f} ms (numpy.genfromtxt: {theirs * 1e3:.1f} ms, "
          f"{theirs / ours:.1f}x slower)")

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
    out.write()


if __name__ == "__main__":
    main()
