"""Every example of README.md and docs/*.md runs as a test (Sybil).

- A ``python`` block runs as written; one that starts with ``>>>`` is a doctest whose
  printed output must match (``...`` stands for any text).
- A ``console`` block is a shell session: each ``$ command`` runs in bash and what it
  prints (stdout and stderr) must match the lines below it, ``...`` again for any text;
  a command that fails must show its error there.
- Blocks in other languages (``sh`` for commands that start a server or the whole suite,
  ``json`` and ``text`` for shapes and output) are not run; ``<!-- skip: next -->``
  skips a block with a reason.

The examples of one page share a namespace and a fresh working directory, in order, as a
reader would run them. Examples that call the HTTP API read its address from
``BREAKAWAY_URL``; here that is a server started for them (tests/live_server.py).
"""

from __future__ import annotations

import doctest
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from sybil import Sybil
from sybil.parsers.myst import CodeBlockParser, PythonCodeBlockParser, SkipParser

sys.path.insert(0, str(Path(__file__).parent / "tests"))
from live_server import serve  # noqa: E402

FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
#: The venv's commands (breakaway, python) first, as after ``scripts/run``.
BIN = str(Path(sys.executable).parent)


class LazyServer:
    """A server started on first use and stopped at the end of the session."""

    def __init__(self) -> None:
        self._running = None
        self.url = None

    def start(self) -> str:
        if self.url is None:
            # in a folder of its own: the examples' working folders come and go
            home = tempfile.mkdtemp(prefix="breakaway-docs-")
            self._running = serve(cwd=home, data_dir=home)
            self.url = self._running.__enter__()
        return self.url

    def stop(self) -> None:
        if self._running is not None:
            self._running.__exit__(None, None, None)


@pytest.fixture(scope="session")
def example_server():
    server = LazyServer()
    yield server
    server.stop()


def _needs_server(text: str) -> bool:
    return "BREAKAWAY_URL" in text


def run_console(example) -> str | None:
    """Each ``$ command`` of a console block, its output checked like a doctest's."""
    namespace = example.namespace
    if _needs_server(example.parsed):
        os.environ["BREAKAWAY_URL"] = namespace["example_server"].start()
    sessions, command, expected = [], None, []
    for line in example.parsed.splitlines():
        if line.startswith("$ "):
            if command is not None:
                sessions.append((command, expected))
            command, expected = line[2:], []
        elif command is not None:
            expected.append(line)
    if command is not None:
        sessions.append((command, expected))
    checker = doctest.OutputChecker()
    env = {**os.environ, "PATH": BIN + os.pathsep + os.environ.get("PATH", "")}
    for command, expected in sessions:
        done = subprocess.run(["bash", "-c", command], cwd=namespace["workdir"], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=600)
        want = "\n".join(expected).strip() + "\n"
        got = done.stdout.strip() + "\n"
        if done.returncode != 0 and not "".join(expected).strip():
            return f"$ {command}\nexited with {done.returncode}:\n{done.stdout}"
        if not checker.check_output(want, got, FLAGS):
            return f"$ {command}\nexpected:\n{want}got:\n{got}"
    return None


class PythonExamples(PythonCodeBlockParser):
    """Python blocks and doctests, with the example server started for those that
    read ``BREAKAWAY_URL``."""

    def __call__(self, document):
        for region in super().__call__(document):
            evaluate = region.evaluator

            def with_server(example, evaluate=evaluate):
                source = getattr(example.parsed, "source", example.parsed)
                if _needs_server(str(source)):
                    os.environ["BREAKAWAY_URL"] = example.namespace["example_server"].start()
                return evaluate(example)

            region.evaluator = with_server
            yield region


def enter_workdir(namespace) -> None:
    namespace["previous_cwd"] = os.getcwd()
    namespace["workdir"] = tempfile.mkdtemp(prefix="breakaway-example-")
    os.chdir(namespace["workdir"])


def leave_workdir(namespace) -> None:
    os.chdir(namespace["previous_cwd"])
    shutil.rmtree(namespace["workdir"], ignore_errors=True)


pytest_collect_file = Sybil(
    parsers=[PythonExamples(doctest_optionflags=FLAGS),
             CodeBlockParser("console", run_console),
             SkipParser()],
    patterns=["README.md", "docs/*.md"],
    setup=enter_workdir,
    teardown=leave_workdir,
    fixtures=["example_server"],
).pytest()
