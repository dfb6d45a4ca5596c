"""The identification loop on the measured BRFD runs: the real-data table.

Data: the BRFD runs (ARTS-Lab, Dataset-Friction-Damper-with-Backlash, CC BY-SA 4.0) as
converted to SI CSVs, in the team's shared data folder beside the checkout by default.
Run: .venv/bin/python benchmarks/brfd_table.py [DATA_DIR]
The table goes to docs/benchmarks/results/brfd.md, which the documentation includes.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from results import Results  # noqa: E402

from breakaway.identify import diagnose, read_csv, report  # noqa: E402

DEFAULT_DIR = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "brfd"


def warnings(r: dict) -> str:
    """The warning codes, each with its parameter."""
    return ", ".join(f"{w['code']}" + (f" ({w['parameter']})" if w["parameter"] else "")
                     for w in r["warnings"]) or "none"


def structure(r: dict) -> str:
    """The two variables the final residual depends on most."""
    return ", ".join(f"{s['against']} {100 * s['strength']:.0f} %"
                     for s in r["residual_structure"][:2]) or "white"


def main(folder: Path) -> None:
    out = Results("brfd", __file__)
    rows = []
    for path in sorted(folder.glob("*.csv")):
        data = read_csv(path)
        t0 = time.perf_counter()
        r = report(diagnose(data))
        seconds = time.perf_counter() - t0
        rows.append([f"`{path.name}`", r["n"], ", ".join(r["effects"]) or "none",
                     f"{r['error_before']:.0f} → {r['error_after']:.0f}",
                     f"{r['heldout']['before']:.0f} → {r['heldout']['after']:.0f}",
                     f"{r['noise_floor']:.1f}", "yes" if r["unexplained"] else "no",
                     warnings(r), structure(r), f"{seconds:.1f}"])
        print(f"{path.name}: {seconds:.1f} s", flush=True)
    out.table(["run", "rows", "effects found", "RMSE before → after [N]",
               "held-out before → after [N]", "noise floor [N]", "unexplained", "warnings",
               "residual depends most on", "time [s]"], rows)
    out.write()


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_DIR)
