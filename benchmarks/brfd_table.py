"""The identification loop on the measured BRFD runs: the README's real-data table.

Data: ../shared/data/brfd/ (ARTS-Lab, Dataset-Friction-Damper-with-Backlash, CC BY-SA 4.0).
Run: .venv/bin/python benchmarks/brfd_table.py [DATA_DIR]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from breakaway.identify import diagnose, read_csv, report

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
    print("| run | rows | effects found | RMSE before → after [N] | held-out before → after [N] "
          "| noise floor [N] | unexplained | warnings | residual depends most on | time [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in sorted(folder.glob("*.csv")):
        data = read_csv(path)
        t0 = time.perf_counter()
        r = report(diagnose(data))
        seconds = time.perf_counter() - t0
        print(f"| `{path.name}` | {r['n']} | {', '.join(r['effects']) or 'none'} | "
              f"{r['error_before']:.0f} → {r['error_after']:.0f} | "
              f"{r['heldout']['before']:.0f} → {r['heldout']['after']:.0f} | "
              f"{r['noise_floor']:.1f} | {'yes' if r['unexplained'] else 'no'} | "
              f"{warnings(r)} | {structure(r)} | {seconds:.1f} |", flush=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_DIR)
