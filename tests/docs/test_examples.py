"""Every code block of the README and the docs is either run by the suite (``python``
and ``console`` blocks, conftest.py) or is one of the few kinds that cannot run there:
so an example cannot escape the tests by being written in another language."""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
PAGES = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
FENCE = re.compile(r"^```(\S*)[^\n]*\n(.*?)^```", re.M | re.S)
#: Run by the suite.
RUN = {"python", "console"}
#: Not code: equations, shapes, output; a proxy's configuration; the docs' directives.
NOT_CODE = {"text", "json", "nginx", "{eval-rst}", "{toctree}", "{include}"}
#: ``sh`` holds only commands that start a server, the whole suite, the docs build or
#: Docker: what a test run cannot run inside itself.
SERVING = ("scripts/run", "scripts/test", "scripts/docs", "breakaway serve", "docker ")


def _blocks():
    for page in PAGES:
        for match in FENCE.finditer(page.read_text(encoding="utf-8")):
            yield page.relative_to(REPO), match.group(1), match.group(2)


def test_every_block_is_run_or_is_not_code():
    kinds = {(str(page), language) for page, language, _ in _blocks()
             if language not in RUN | NOT_CODE | {"sh"}}
    assert kinds == set()


def test_sh_blocks_only_start_servers_suites_or_docker():
    commands = [(str(page), line) for page, language, body in _blocks() if language == "sh"
                for line in body.splitlines() if line.strip()]
    assert commands, "the README's set-up block is sh"
    assert [(page, line) for page, line in commands if not line.startswith(SERVING)] == []


def test_the_readme_and_every_page_have_examples_that_run():
    runnable = {str(page) for page, language, _ in _blocks() if language in RUN}
    for name in ("README.md", "docs/model.md", "docs/identification.md", "docs/cli.md",
                 "docs/http-api.md", "docs/export.md"):
        assert name in runnable, name
