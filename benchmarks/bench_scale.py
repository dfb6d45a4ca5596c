"""Identification at scale: a 1,000,000-row time series (about 17 minutes at 1 kHz).

Writes a seeded synthetic CSV (viscous friction present, undeclared), then runs
``read_csv`` + the full diagnosis in a fresh process and prints the wall time and the
peak resident memory. The obvious alternative, the same diagnosis without screening
(every candidate fitted on every row), runs in the same way on a shorter record and is
extrapolated linearly in rows (it is at least linear: every fit touches every row).

Run: .venv/bin/python benchmarks/bench_scale.py [--rows N] [--alternative-rows M]
The table goes to docs/benchmarks/results/scale.md, which the documentation includes.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results import Results  # noqa: E402

CHILD = textwrap.dedent("""
    import json, resource, sys, time
    from breakaway.identify import diagnose, read_csv, report, screening
    path, screen = sys.argv[1], sys.argv[2] == "screen"
    if not screen:
        screening.SCREEN_ROWS = 10**12
    t0 = time.perf_counter()
    data = read_csv(path, max_bytes=None)
    parsed = time.perf_counter() - t0
    result = report(diagnose(data))
    total = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(json.dumps({"rows": data.n, "parse_s": parsed, "total_s": total, "peak_mb": peak,
                      "effects": result["effects"], "rmse_before": result["error_before"],
                      "rmse_after": result["error_after"], "white": result["residual_white"],
                      "screened_rows": result["screened_rows"]}))
""")


def make_csv(rows: int, path: str, count: float = 0.0) -> None:
    """The seeded record, its positions read by an encoder of ``count`` [m] when given
    (the measured-x path: the model's positions, a, the floor's x part)."""
    from dataclasses import replace

    import numpy as np

    from breakaway.identify.synthetic import make_dataset, to_csv

    data, _ = make_dataset("timeseries", ("viscous",), seed=3, n=rows)
    if count:
        data = replace(data, columns={**data.columns,
                                      "x": np.round(data.columns["x"] / count) * count})
    with open(path, "w") as fh:
        fh.write(to_csv(data))


def run(path: str, mode: str) -> dict:
    out = subprocess.run([sys.executable, "-c", CHILD, path, mode], capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--alternative-rows", type=int, default=100_000)
    args = parser.parse_args()
    out = Results("scale", __file__)
    with tempfile.TemporaryDirectory() as tmp:
        big, small = os.path.join(tmp, "big.csv"), os.path.join(tmp, "small.csv")
        counts = os.path.join(tmp, "counts.csv")
        make_csv(args.rows, big)
        make_csv(args.rows, counts, count=1e-6)
        make_csv(args.alternative_rows, small)
        size = os.path.getsize(big) / 1e6
        screened = run(big, "screen")
        encoder = run(counts, "screen")
        plain = run(small, "plain")
    scale = args.rows / args.alternative_rows
    print(f"CPU cores: {os.cpu_count()}, Python {sys.version.split()[0]}")
    print(f"{screened['rows']:,} rows ({size:.0f} MB CSV), screened on "
          f"{screened['screened_rows']:,} rows in blocks:")
    print(f"  parse {screened['parse_s']:.1f} s, parse + diagnosis {screened['total_s']:.1f} s, "
          f"peak RSS {screened['peak_mb']:.0f} MB")
    print(f"  effects {screened['effects']}, RMSE {screened['rmse_before']:.4g} -> "
          f"{screened['rmse_after']:.4g} N, white {screened['white']}")
    print(f"the same read by a 1 um encoder: parse + diagnosis {encoder['total_s']:.1f} s, "
          f"peak RSS {encoder['peak_mb']:.0f} MB, effects {encoder['effects']}, RMSE "
          f"{encoder['rmse_before']:.4g} -> {encoder['rmse_after']:.4g} N")
    print(f"without screening, {plain['rows']:,} rows: {plain['total_s']:.1f} s "
          f"(effects {plain['effects']}, peak RSS {plain['peak_mb']:.0f} MB); "
          f"x{scale:g} rows -> about {plain['total_s'] * scale:.0f} s")
    print(f"speed-up at {args.rows:,} rows: about {plain['total_s'] * scale / screened['total_s']:.0f}x")
    print()

    def effects(run):
        return ", ".join(run["effects"]) or "none"

    out.table(["record", "parse", "parse + diagnosis", "peak RSS", "effects found",
               "RMSE before → after [N]"], [
        [f"{screened['rows']:,} rows ({size:.0f} MB CSV), screened on "
         f"{screened['screened_rows']:,} rows in blocks", f"{screened['parse_s']:.1f} s",
         f"{screened['total_s']:.1f} s", f"{screened['peak_mb']:.0f} MB", effects(screened),
         f"{screened['rmse_before']:.3g} → {screened['rmse_after']:.3g}"],
        ["the same read by a 1 µm encoder", "", f"{encoder['total_s']:.1f} s",
         f"{encoder['peak_mb']:.0f} MB", effects(encoder),
         f"{encoder['rmse_before']:.3g} → {encoder['rmse_after']:.3g}"],
        [f"without screening, {plain['rows']:,} rows", "", f"{plain['total_s']:.1f} s "
         f"(×{scale:g} rows: about {plain['total_s'] * scale:.0f} s)",
         f"{plain['peak_mb']:.0f} MB", effects(plain),
         f"{plain['rmse_before']:.3g} → {plain['rmse_after']:.3g}"],
    ])
    out.write()


if __name__ == "__main__":
    main()
