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


def main(folder: Path) -> None:
    print("| run | rows | effects found | RMSE before → after [N] | held-out before → after [N] "
          "| noise floor [N] | white | unexplained | time [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in sorted(folder.glob("*.csv")):
        data = read_csv(path)
        t0 = time.perf_counter()
        r = report(diagnose(data))
        seconds = time.perf_counter() - t0
        print(f"| `{path.name}` | {r['n']} | {', '.join(r['effects']) or 'none'} | "
              f"{r['error_before']:.0f} → {r['error_after']:.0f} | "
              f"{r['heldout']['before']:.0f} → {r['heldout']['after']:.0f} | "
              f"{r['noise_floor']:.1f} | {'yes' if r['residual_white'] else 'no'} | "
              f"{'yes' if r['unexplained'] else 'no'} | {seconds:.1f} |", flush=True)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else DEFAULT_DIR)
