"""Identification at scale: a 1,000,000-row time series (about 17 minutes at 1 kHz).

Writes a seeded synthetic CSV (viscous friction present, undeclared), then runs
``read_csv`` + the full diagnosis in a fresh process and prints the wall time and the
peak resident memory. The obvious alternative, the same diagnosis without screening
(every candidate fitted on every row), runs in the same way on a shorter record and is
extrapolated linearly in rows (it is at least linear: every fit touches every row).

Run: .venv/bin/python benchmarks/bench_scale.py [--rows N] [--alternative-rows M]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import textwrap

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


def make_csv(rows: int, path: str) -> None:
    from breakaway.identify.synthetic import make_dataset, to_csv

    data, _ = make_dataset("timeseries", ("viscous",), seed=3, n=rows)
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
    with tempfile.TemporaryDirectory() as tmp:
        big, small = os.path.join(tmp, "big.csv"), os.path.join(tmp, "small.csv")
        make_csv(args.rows, big)
        make_csv(args.alternative_rows, small)
        size = os.path.getsize(big) / 1e6
        screened = run(big, "screen")
        plain = run(small, "plain")
    scale = args.rows / args.alternative_rows
    print(f"CPU cores: {os.cpu_count()}, Python {sys.version.split()[0]}")
    print(f"{screened['rows']:,} rows ({size:.0f} MB CSV), screened on "
          f"{screened['screened_rows']:,} rows in blocks:")
    print(f"  parse {screened['parse_s']:.1f} s, parse + diagnosis {screened['total_s']:.1f} s, "
          f"peak RSS {screened['peak_mb']:.0f} MB")
    print(f"  effects {screened['effects']}, RMSE {screened['rmse_before']:.4g} -> "
          f"{screened['rmse_after']:.4g} N, white {screened['white']}")
    print(f"without screening, {plain['rows']:,} rows: {plain['total_s']:.1f} s "
          f"(effects {plain['effects']}, peak RSS {plain['peak_mb']:.0f} MB); "
          f"x{scale:g} rows -> about {plain['total_s'] * scale:.0f} s")
    print(f"speed-up at {args.rows:,} rows: about {plain['total_s'] * scale / screened['total_s']:.0f}x")


if __name__ == "__main__":
    main()
