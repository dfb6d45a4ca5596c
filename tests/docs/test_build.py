"""The documentation builds offline with no warning, and what it builds stands alone."""

from __future__ import annotations

import re

import pytest

#: Resources a page loads (scripts, styles, images, fonts), not the links it shows.
LOADED = re.compile(r"""<(?:script|img|iframe|source)\b[^>]*\bsrc=["']([^"']+)|"""
                    r"""<link\b[^>]*\bhref=["']([^"']+)|url\(["']?([^"')]+)""")


@pytest.fixture(scope="module")
def html(built_docs):
    folder, done = built_docs
    assert done.returncode == 0, f"the docs do not build:\n{done.stderr[-4000:]}"
    return folder


def test_the_docs_build_without_a_warning(built_docs):
    folder, done = built_docs
    assert done.returncode == 0 and done.stderr.strip() == "", done.stderr[-4000:]
    assert (folder / "index.html").is_file()


def test_pages_load_nothing_from_outside(html):
    outside = []
    for path in sorted(html.rglob("*.html")) + sorted(html.rglob("*.css")):
        for match in LOADED.finditer(path.read_text(encoding="utf-8", errors="replace")):
            target = next(group for group in match.groups() if group)
            if re.match(r"(https?:)?//", target):
                outside.append(f"{path.relative_to(html)}: {target}")
    assert outside == []


def test_the_python_reference_is_generated_from_the_docstrings(html):
    page = (html / "python-api.html").read_text(encoding="utf-8")
    for name in ("breakaway.steady.steady_state_force", "breakaway.presliding.presliding_force",
                 "breakaway.quasistatic.breakaway_force", "breakaway.dynamics.simulate_loop",
                 "breakaway.identify.identify", "breakaway.identify.read_csv"):
        assert f'id="{name}"' in page, name
    # numpydoc turned a Parameters section into a field list with its units
    assert "Stribeck velocity" in page and "[m/s]" in page
