"""Command line: ``breakaway serve`` and ``breakaway fit`` (MODEL.md §9)."""

from __future__ import annotations

import argparse
import sys

from . import __version__


def _serve(args: argparse.Namespace) -> int:
    import uvicorn

    from .settings import get_settings

    settings = get_settings()
    uvicorn.run("breakaway.api.app:create_app", factory=True,
                host=args.host or settings.host, port=args.port or settings.port)
    return 0


def _fit(args: argparse.Namespace) -> int:
    import json

    from .identify import DataError, FitError, identify, read_csv
    from .identify.text import format_report

    try:
        data = read_csv(args.file, kind=args.kind)
        result = identify(data, progress=_progress_line(data.n))
    except (DataError, FitError) as err:
        print(f"breakaway fit: {args.file}: {err}", file=sys.stderr)
        return 2
    if args.json:
        print(json.dumps(result, indent=2))
    else:
        print(format_report(result, source=args.file), end="")
    return 0


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
    serve.set_defaults(handler=_serve)
    fit = commands.add_parser("fit", help="fit a measured CSV and report the effects found")
    fit.add_argument("file", help="CSV file (MODEL.md §6)")
    fit.add_argument("--kind", choices=("timeseries", "steady", "breakaway"), default=None,
                     help="data kind (default: from a '# kind:' line or the columns)")
    fit.add_argument("--json", action="store_true", help="print the JSON report (MODEL.md §8)")
    fit.set_defaults(handler=_fit)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    return args.handler(args)


if __name__ == "__main__":
    sys.exit(main())
