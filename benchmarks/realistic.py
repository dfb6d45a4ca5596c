"""Identification on machine-like recordings (issue 19): what each report says against
what it must say.

Every family of ``tests/identify/machines.py`` (a servo axis under a torque command,
joint friction curves, presliding records, stick-slip creep, encoder counts logged in
degrees, and machine-like versions of issue 9's classes) is generated for a few seeds,
written as CSV, parsed and identified exactly as ``breakaway fit FILE`` does, and
checked by the tests' own :func:`~identify.expectations.failures`. The table
prints the expected effects and warnings, the reported effects, the key warnings, the
parameters the report determines beside the truth, and the seconds of each fit; below
it, each miss. The obvious alternative (the engine's own seeded sets from
``breakaway.identify.synthetic``, where the model is the generator) is what the test
suite already passes; this is the gap between that and a machine.

Run: .venv/bin/python benchmarks/realistic.py [--seeds 3] [--family NAME ...]
The table goes to docs/benchmarks/results/realistic.md, which the documentation includes.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

# imported as pytest imports them (package ``identify`` under tests/), so that the
# plant's numba cache, keyed by module name, serves both
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from results import Results  # noqa: E402

from breakaway.identify import identify, parse_csv  # noqa: E402
from identify.expectations import failures  # noqa: E402
from identify.machines import families  # noqa: E402

#: Warning codes the table shows (the others are in the reports).
KEY_WARNINGS = ("quantised", "force-is-command", "one-direction", "single-rate", "beyond-data",
                "stick-slip", "indistinguishable")


def _determined(report, truth) -> str:
    final = report["final"]
    shown = []
    for name, value in final["params"].items():
        if not final["determined"].get(name) or value is None:
            continue
        true = truth.get(name if name != "Fs" or "level" not in truth else "level")
        shown.append(f"{name} {value:.3g}" + (f" ({true:.3g})" if true is not None else ""))
    return ", ".join(shown) or "none"


def _warnings(report) -> str:
    seen = []
    for w in report["warnings"]:
        if w["code"] in KEY_WARNINGS:
            text = w["code"] + (f"({w['parameter']})" if w["parameter"] else "")
            if text not in seen:
                seen.append(text)
    return ", ".join(seen) or "-"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=3, help="seeds 0 … N−1 per family")
    parser.add_argument("--family", action="append", help="only these families")
    args = parser.parse_args()
    chosen = families()
    if args.family:
        chosen = {name: chosen[name] for name in args.family}
    out = Results("realistic", __file__)
    rows, misses, passed, total, started = [], [], 0, 0, time.perf_counter()
    for name, make in chosen.items():
        for seed in range(args.seeds):
            recording = make(seed)
            t0 = time.perf_counter()
            report = identify(parse_csv(recording.csv))
            seconds = time.perf_counter() - t0
            found = failures(report, recording.expect)
            total += 1
            passed += not found
            misses += [(name, seed, f) for f in found]
            rows.append([name, seed, recording.expect.summary(),
                         ", ".join(report["effects"]) or "none", _warnings(report),
                         _determined(report, recording.truth),
                         "yes" if report["unexplained"] else "no", f"{seconds:.1f}",
                         len(found) or "pass"])
            print(f"{name} seed {seed}: {seconds:.1f} s, {len(found) or 'pass'}", flush=True)
    out.note(f"**{passed} of {total} recordings get the report they must** "
             f"({time.perf_counter() - started:.0f} s in all).")
    out.table(["family", "seed", "expected", "reported effects", "key warnings",
               "determined (truth)", "unexplained", "s", "misses"], rows)
    if misses:
        out.note("Misses:\n\n" + "\n".join(f"- {name} seed {seed}: {text}"
                                            for name, seed, text in misses))
    out.write()


if __name__ == "__main__":
    main()
