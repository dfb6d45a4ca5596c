"""A real ``breakaway serve`` (uvicorn in a subprocess) on a free port, for the browser
tests and the documentation's HTTP examples."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path
from typing import Iterator

import pytest


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@contextlib.contextmanager
def serve(cwd: str | None = None, **settings: str) -> Iterator[str]:
    """The server's base URL while it runs in ``cwd``, with ``BREAKAWAY_<NAME>`` settings
    given; a server that exits or does not answer /api/health within 60 s fails the test.
    (A server's working directory must outlive it: it starts its fit workers there.)"""
    port = free_port()
    env = {**os.environ, **{f"BREAKAWAY_{name.upper()}": str(value)
                            for name, value in settings.items()}}
    log = open(Path(os.environ.get("TMPDIR", "/tmp")) / f"breakaway-server-{port}.log", "w")
    process = subprocess.Popen([sys.executable, "-m", "breakaway", "serve", "--host",
                                "127.0.0.1", "--port", str(port)], stdout=log,
                               stderr=subprocess.STDOUT, env=env, cwd=cwd)
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 60
        while True:
            if process.poll() is not None:
                pytest.fail(f"the server exited with {process.returncode}; see {log.name}")
            try:
                with urllib.request.urlopen(f"{url}/api/health", timeout=1) as response:
                    if response.status == 200:
                        break
            except OSError:
                pass
            if time.monotonic() > deadline:
                pytest.fail("the server did not answer /api/health within 60 s")
            time.sleep(0.1)
        yield url
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
        log.close()
