"""Identification on measured recordings from real rigs (issue 26): runs the judge of the
development set on this checkout's ``breakaway`` and prints its table, its summary and
a count by rig.

The recordings and their judge live outside the repository (they may not be copied into
it): by default in ``../shared/realdata-dev`` beside the checkout, or where
``--data DIR`` or the environment variable ``BREAKAWAY_REALDATA`` say. A new user has no
such folder: the script then says so and exits 0.

Run: .venv/bin/python benchmarks/realdata.py [-j 2] [--data DIR] [--save DIR] [--timeout S]
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from results import Results  # noqa: E402
#: Where the development set is looked for when neither option nor variable says.
DEFAULT = ROOT.parent / "shared" / "realdata-dev"
#: One judged line: ``STATUS file: …``.
LINE = re.compile(r"^(OK|WRONG|WARN-MISSING|FAIL) ([^:]+):")


def breakaway_command() -> str:
    """This checkout's command line tool (its ``.venv``), else this interpreter's module."""
    tool = ROOT / ".venv" / "bin" / "breakaway"
    if tool.exists():
        return shlex.quote(str(tool))
    return f"{shlex.quote(sys.executable)} -m breakaway"


def by_rig(lines) -> dict[str, dict[str, int]]:
    """Judged lines counted by status per rig (the file name up to its first ``_``)."""
    counts: dict[str, dict[str, int]] = {}
    for line in lines:
        match = LINE.match(line)
        if match:
            status, name = match.groups()
            rig = counts.setdefault(name.split("_")[0], {})
            rig[status] = rig.get(status, 0) + 1
    return counts


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", help="the development set's folder (holds judge.py and "
                        "csv/); default $BREAKAWAY_REALDATA or ../shared/realdata-dev")
    parser.add_argument("-j", type=int, default=2, help="parallel fits (default 2)")
    parser.add_argument("--save", metavar="DIR", help="write each report to DIR")
    parser.add_argument("--timeout", type=int, default=240,
                        help="seconds per fit before the judge calls it a failure (default 240; "
                        "more on a machine others share)")
    args = parser.parse_args()

    folder = Path(args.data or os.environ.get("BREAKAWAY_REALDATA") or DEFAULT)
    judge, recordings = folder / "judge.py", folder / "csv"
    if not (judge.is_file() and recordings.is_dir()):
        print(f"no development recordings at {folder} (judge.py and csv/ are not there): "
              "nothing to judge. They are not part of the project; give their folder with "
              "--data or BREAKAWAY_REALDATA.")
        return 0
    command = [sys.executable, str(judge), str(recordings), "--cmd", breakaway_command(),
               "-j", str(args.j), "--timeout", str(args.timeout)] \
        + (["--save", args.save] if args.save else [])
    print(f"judging {sum(1 for _ in recordings.glob('*.csv'))} recordings in {recordings} "
          f"with {breakaway_command()} (-j {args.j}); load average before: "
          f"{', '.join(f'{x:.2f}' for x in os.getloadavg())}", flush=True)
    started = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    print(result.stdout, end="")
    if result.stderr:
        print(result.stderr, end="", file=sys.stderr)
    lines = result.stdout.splitlines()
    out = Results("realdata", __file__)
    statuses = ("OK", "WARN-MISSING", "WRONG", "FAIL")
    out.table(["rig", *statuses], [[rig, *(counts.get(s, 0) for s in statuses)]
                                   for rig, counts in sorted(by_rig(lines).items())])
    misses = [line.split(" — ", 1) for line in lines if LINE.match(line)
              and not line.startswith("OK ")]
    if misses:
        out.table(["recording", "why the judge does not accept it"],
                  [[LINE.match(head).group(2), why if len(rest) else ""]
                   for head, *rest in misses for why in (rest[0] if rest else "",)])
    summary = next((line for line in lines if line.startswith("realdata:")), "")
    out.note(f"{summary.removeprefix('realdata: ')}; {time.perf_counter() - started:.0f} s "
             f"for {sum(1 for _ in recordings.glob('*.csv'))} fits (-j {args.j}); the judge "
             f"exits {result.returncode} ({'its targets met' if result.returncode == 0 else 'its targets not met'}).")
    out.write()
    return result.returncode


if __name__ == "__main__":
    sys.exit(main())
