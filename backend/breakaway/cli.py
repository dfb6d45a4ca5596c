"""Command line: ``breakaway serve``, ``breakaway fit``, ``breakaway export`` and
``breakaway plan`` (documented on the command-line page of the documentation)."""

from __future__ import annotations

import argparse
import sys

from . import __version__


def _serve(args: argparse.Namespace) -> int:
    import uvicorn

    from .settings import get_settings

    settings = get_settings()
    # several worker processes share the port (the kernel spreads connections) and,
    # through the data directory's job store, the fit jobs; the explorer is stateless
    uvicorn.run("breakaway.api.app:create_app", factory=True, workers=args.workers,
                host=args.host or settings.host, port=args.port or settings.port)
    return 0


def _fit(args: argparse.Namespace) -> int:
    import json

    from .identify import DataError, FitError, identify, read_csv
    from .identify.text import format_report

    if len(args.files) > 1 or args.summary or args.dask:
        return _fit_many(args)
    path = args.files[0]
    try:
        data = read_csv(path, kind=args.kind)
        result = identify(data, progress=_progress_line(data.n))
    except (DataError, FitError) as err:
        print(f"breakaway fit: {path}: {err}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(format_report(result, source=path), end="")
    return 0


def _export(args: argparse.Namespace) -> int:
    """The fitted model of a report as a Python module, a C file or JSON; a bad report
    is one line on stderr and exit code 2."""
    import json

    from .export import ReportError, export_model

    try:
        with open(args.report, encoding="utf-8") as fh:
            report = json.load(fh)
    except OSError as err:
        print(f"breakaway export: {args.report}: cannot read: {err.strerror}", file=sys.stderr)
        return 2
    except (json.JSONDecodeError, UnicodeDecodeError) as err:
        print(f"breakaway export: {args.report}: not a JSON report: {err}", file=sys.stderr)
        return 2
    try:
        text = export_model(report, args.lang, s=args.s, t_0=args.t0)
    except ReportError as err:
        print(f"breakaway export: {args.report}: {err}", file=sys.stderr)
        return 2
    if args.output:
        try:
            with open(args.output, "w", encoding="utf-8") as fh:
                fh.write(text)
        except OSError as err:
            print(f"breakaway export: {args.output}: cannot write: {err.strerror}",
                  file=sys.stderr)
            return 2
    else:
        sys.stdout.write(text)
    return 0


def _read_json(path: str, command: str) -> tuple[object, int]:
    """A JSON file, or (None, 2) after one line on stderr naming what is wrong."""
    import json

    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh), 0
    except OSError as err:
        print(f"breakaway {command}: {path}: cannot read: {err.strerror}", file=sys.stderr)
    except (json.JSONDecodeError, UnicodeDecodeError) as err:
        print(f"breakaway {command}: {path}: not JSON: {err}", file=sys.stderr)
    return None, 2


def _ranges(items: list[str]) -> dict:
    """``--range V=0.001:0.1`` → {"V": (0.001, 0.1)}."""
    out = {}
    for item in items:
        name, _, span = item.partition("=")
        low, _, high = span.partition(":")
        try:
            out[name.strip()] = (float(low), float(high))
        except ValueError:
            raise SystemExit(f"breakaway plan: --range {item!r}: expected NAME=LOW:HIGH") from None
    return out


def _plan(args: argparse.Namespace) -> int:
    """The next experiment for a report (or parameters); the programme to ``-o``; a bad
    input is one line on stderr and exit code 2."""
    import json

    from .plan import PlanError, plan_experiment
    from .plan.text import format_plan

    if (args.report is None) == (args.params is None):
        print("breakaway plan: give a REPORT.json or --params JSON, not both", file=sys.stderr)
        return 2
    report = params = None
    if args.report is not None:
        report, code = _read_json(args.report, "plan")
        if code:
            return code
    else:
        try:
            params = json.loads(args.params)
        except json.JSONDecodeError as err:
            print(f"breakaway plan: --params: not JSON: {err}", file=sys.stderr)
            return 2
        if not isinstance(params, dict):
            print("breakaway plan: --params must be a JSON object", file=sys.stderr)
            return 2
    limits = {"u_max": args.u_max, "v_max": args.v_max, "v_min": args.v_min,
              "travel": args.travel, "duration": args.duration, "sample_rate": args.sample_rate}
    targets = [t.strip() for t in args.targets.split(",") if t.strip()] if args.targets else None
    try:
        result = plan_experiment(args.family, report=report, params=params, limits=limits,
                                 runs=args.runs, noise=args.noise, targets=targets,
                                 ranges=_ranges(args.range) or None, grid=args.grid)
    except PlanError as err:
        where = args.report or "--params"
        print(f"breakaway plan: {where}: {'.'.join(map(str, err.path))}: {err}", file=sys.stderr)
        return 2
    if args.output:
        try:
            with open(args.output, "w", encoding="utf-8") as fh:
                fh.write(result["programme"])
        except OSError as err:
            print(f"breakaway plan: {args.output}: cannot write: {err.strerror}", file=sys.stderr)
            return 2
    if args.json:
        print(json.dumps(result, indent=2, ensure_ascii=False))
    else:
        print(format_plan(result, args.output), end="")
    return 0


#: Columns of the batch summary, one row per file.
SUMMARY_COLUMNS = ("file", "kind", "rows", "effects", "error_before", "error_after",
                   "heldout_before", "heldout_after", "noise_floor", "unexplained",
                   "warnings", "seconds", "error")


def summary_row(path: str, kind: str | None, content: bytes | None = None) -> dict:
    """Identify one file (in a worker process, local or on a Dask cluster): its row of
    the batch summary. ``content``: the file's bytes, read where the command runs, for
    workers that do not share its file system."""
    from .identify import DataError, FitError, identify, parse_csv, read_csv

    row = dict.fromkeys(SUMMARY_COLUMNS, None)
    row["file"] = path
    try:
        data = read_csv(path, kind=kind) if content is None else parse_csv(content, kind)
        report = identify(data)
    except (DataError, FitError) as err:
        row["error"] = str(err)[:500]
        return row
    row.update(kind=report["kind"], rows=report["n"], effects=" ".join(report["effects"]),
               error_before=report["error_before"], error_after=report["error_after"],
               heldout_before=report["heldout"]["before"],
               heldout_after=report["heldout"]["after"], noise_floor=report["noise_floor"],
               unexplained=report["unexplained"], seconds=report["seconds"],
               warnings=" ".join(sorted({w["code"] for w in report["warnings"]})))
    return row


def _fit_many(args: argparse.Namespace) -> int:
    """Several files: identified on ``--jobs`` local processes, one summary row each,
    as CSV (stdout, or PREFIX.csv) and JSON (``--json``, or PREFIX.json)."""
    import csv
    import io
    import json
    from concurrent.futures import ProcessPoolExecutor

    jobs = max(1, args.jobs)
    if args.dask:
        rows = _rows_on_dask(args.dask, args.files, args.kind)
    elif jobs == 1:
        rows = [summary_row(path, args.kind) for path in args.files]
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            rows = list(pool.map(summary_row, args.files, [args.kind] * len(args.files)))
    table = io.StringIO()
    writer = csv.DictWriter(table, fieldnames=SUMMARY_COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(rows)
    if args.summary:
        with open(f"{args.summary}.csv", "w", encoding="utf-8") as fh:
            fh.write(table.getvalue())
        with open(f"{args.summary}.json", "w", encoding="utf-8") as fh:
            json.dump(rows, fh, indent=2)
    if args.json:
        print(json.dumps(rows, indent=2))
    elif not args.summary:
        print(table.getvalue(), end="")
    failed = [row["file"] for row in rows if row["error"]]
    for row in rows:
        if row["error"]:
            print(f"breakaway fit: {row['file']}: {row['error']}", file=sys.stderr)
    return 2 if failed else 0


def _rows_on_dask(address: str, paths: list[str], kind: str | None) -> list[dict]:
    """The summary rows computed on the Dask cluster at ``address``; each file's bytes
    travel with its task, so the workers need breakaway installed, not the files."""
    try:
        from dask.distributed import Client
    except ImportError:
        raise SystemExit("breakaway fit: --dask needs dask.distributed; install it with "
                         "pip install 'breakaway[dask]'") from None
    contents = []
    for path in paths:
        try:
            with open(path, "rb") as fh:
                contents.append(fh.read())
        except OSError:
            contents.append(None)  # read_csv on the worker names the problem
    with Client(address) as client:
        futures = client.map(summary_row, paths, [kind] * len(paths), contents, pure=False)
        return client.gather(futures)


#: Fits of at least this many rows print a progress line on stderr.
PROGRESS_ROWS = 50_000


def _progress_line(rows: int):
    """A progress callback for long fits: one updating line on a terminal, one line per
    stage otherwise (logs); None for short fits."""
    if rows < PROGRESS_ROWS:
        return None
    import time

    started = time.perf_counter()
    tty = sys.stderr.isatty()
    last = [None]

    def show(fraction: float, message: str) -> None:
        text = f"breakaway fit: {100 * fraction:3.0f} % {message} ({time.perf_counter() - started:.1f} s)"
        if tty:
            end = "\n" if fraction >= 1 else ""
            print(f"\r{text:<79}", end=end, file=sys.stderr, flush=True)
        elif message.split()[0] != last[0]:
            print(text, file=sys.stderr, flush=True)
        last[0] = message.split()[0]
    return show


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="breakaway", description=__doc__)
    parser.add_argument("--version", action="version", version=f"breakaway {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    serve = commands.add_parser("serve", help="run the explorer (http://127.0.0.1:8000)")
    serve.add_argument("--host", default=None, help="bind address (default 127.0.0.1)")
    serve.add_argument("--port", type=int, default=None, help="port (default 8000)")
    serve.add_argument("--workers", type=int, default=1,
                       help="server processes sharing the port and the job store (default 1)")
    serve.set_defaults(handler=_serve)
    fit = commands.add_parser("fit", help="fit measured CSVs and report the effects found")
    fit.add_argument("files", nargs="+", metavar="FILE",
                     help="CSV file(s): timeseries t,x,F; steady v,F; breakaway k,F_ba; "
                          "several give one summary row each")
    fit.add_argument("--jobs", type=int, default=1,
                     help="local worker processes for several files (default 1)")
    fit.add_argument("--dask", metavar="ADDRESS", default=None,
                     help="run the files on an existing Dask cluster (tcp://host:8786) "
                          "instead of local processes; needs breakaway[dask]")
    fit.add_argument("--summary", metavar="PREFIX", default=None,
                     help="write the summary table to PREFIX.csv and PREFIX.json")
    fit.add_argument("--kind", choices=("timeseries", "steady", "breakaway"), default=None,
                     help="data kind (default: from a '# kind:' line or the columns)")
    fit.add_argument("--json", action="store_true", help="print the JSON identification report")
    fit.set_defaults(handler=_fit)
    export = commands.add_parser(
        "export", help="the fitted model of a report as standalone Python, C99 or JSON")
    export.add_argument("report", metavar="REPORT.json",
                        help="a report of breakaway fit FILE --json")
    export.add_argument("--lang", choices=("python", "c", "json"), required=True,
                        help="python: steady(v), class Presliding with step(x, t); c: "
                             "bk_steady, bk_state, bk_init, bk_step; json: the parameters")
    export.add_argument("-o", "--output", metavar="FILE", default=None,
                        help="write to FILE (default: standard output)")
    export.add_argument("--s", type=float, default=None,
                        help="presliding scale [1/m] where the report has none (a steady fit)")
    export.add_argument("--t0", type=float, default=None,
                        help="the time [s] a drift refers to, where the report has no t_0")
    export.set_defaults(handler=_export)
    plan = commands.add_parser(
        "plan", help="the next experiment: runs that determine what a report leaves open")
    plan.add_argument("report", metavar="REPORT.json", nargs="?", default=None,
                      help="a report of breakaway fit FILE --json")
    plan.add_argument("--params", metavar="JSON", default=None,
                      help='model parameters instead of a report, e.g. \'{"Fc": 1, "Fs": 1.5}\'')
    plan.add_argument("--family", choices=("ramps", "steady", "sine"), required=True,
                      help="ramps: force ramps at chosen rates (break-away forces); steady: "
                           "speed set-points both ways; sine: one position sine through "
                           "presliding and reversals")
    plan.add_argument("--u-max", type=float, default=None,
                      help="largest force the rig applies [N] (default: the record's largest)")
    plan.add_argument("--v-max", type=float, default=None,
                      help="largest speed [m/s] (default: the record's largest)")
    plan.add_argument("--v-min", type=float, default=None,
                      help="slowest speed the rig holds steadily [m/s] (set-points)")
    plan.add_argument("--travel", type=float, default=None, help="travel [m] (the sine)")
    plan.add_argument("--duration", type=float, default=None,
                      help="longest a run may last [s] (default: the record's length, or 60)")
    plan.add_argument("--sample-rate", type=float, default=None,
                      help="samples per second of a record [Hz] (the sine)")
    plan.add_argument("--runs", type=int, default=None, help="runs (ramps, set-points; default 12)")
    plan.add_argument("--noise", type=float, default=None,
                      help="std of one measured force [N] (default: the record's)")
    plan.add_argument("--targets", default=None, metavar="Fs,V",
                      help="parameters to determine (default: those the data do not)")
    plan.add_argument("--range", action="append", default=[], metavar="NAME=LOW:HIGH",
                      help="take a parameter as open over this range (repeatable)")
    plan.add_argument("--grid", type=int, default=None, help="candidate design points")
    plan.add_argument("-o", "--output", metavar="PROGRAMME.csv", default=None,
                      help="write the programme (run,t,u / run,v / t,x) to this file")
    plan.add_argument("--json", action="store_true", help="print the plan as JSON")
    plan.set_defaults(handler=_plan)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    return args.handler(args)


if __name__ == "__main__":
    sys.exit(main())
