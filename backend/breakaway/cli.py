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


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="breakaway", description=__doc__)
    parser.add_argument("--version", action="version", version=f"breakaway {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    serve = commands.add_parser("serve", help="run the explorer (http://127.0.0.1:8000)")
    serve.add_argument("--host", default=None, help="bind address (default 127.0.0.1)")
    serve.add_argument("--port", type=int, default=None, help="port (default 8000)")
    serve.set_defaults(handler=_serve)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    return args.handler(args)


if __name__ == "__main__":
    sys.exit(main())
