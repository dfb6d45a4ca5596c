"""Nothing a reader or a student sees names a file outside the repository: not the
README, not the documentation (its sources and the HTML built from them, which holds
the docstrings), not the explorer's page and modules."""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
OUTSIDE = ("MODEL.md", "../shared")


def _mentions(paths, root) -> list[str]:
    found = []
    for path in paths:
        text = path.read_text(encoding="utf-8", errors="replace")
        for number, line in enumerate(text.splitlines(), 1):
            found += [f"{path.relative_to(root)}:{number}: {line.strip()[:120]}"
                      for name in OUTSIDE if name in line]
    return found


def _files(folder: Path, suffixes) -> list[Path]:
    return sorted(p for p in folder.rglob("*") if p.is_file() and p.suffix in suffixes
                  and "_build" not in p.parts)


def test_the_readme_and_the_doc_sources_name_no_outside_file():
    paths = [REPO / "README.md", *_files(REPO / "docs", {".md", ".py", ".txt", ".html"})]
    assert _mentions(paths, REPO) == []


def test_the_built_docs_name_no_outside_file(built_docs):
    html, done = built_docs
    assert done.returncode == 0, done.stderr[-2000:]
    assert _mentions(_files(html, {".html", ".txt", ".js"}), html) == []


def test_the_explorer_names_no_outside_file():
    assert _mentions(_files(REPO / "frontend", {".html", ".js", ".css", ".md"}), REPO) == []
