"""/guide/: the built documentation, served with a policy that allows exactly each
page's inline scripts; before it is built, a page that says how to build it."""

from __future__ import annotations

import base64
import hashlib

PAGE = ("<!doctype html><html><head><script>window.one = 1;</script>"
        '<script src="_static/x.js"></script></head><body>'
        "<script data-mode>window.two = 2;</script><p>page</p></body></html>")


def _sha(script: str) -> str:
    return "'sha256-" + base64.b64encode(hashlib.sha256(script.encode()).digest()).decode() + "'"


def test_a_built_page_allows_its_own_inline_scripts_and_no_others(make_client, tmp_path):
    (tmp_path / "index.html").write_text(PAGE)
    (tmp_path / "model.html").write_text("<html><body><p>model</p></body></html>")
    with make_client(docs_dir=tmp_path) as client:
        index = client.get("/guide/")
        model = client.get("/guide/model.html")
    assert index.status_code == 200 and "<p>page</p>" in index.text
    policies = index.headers.get_list("content-security-policy")
    assert len(policies) == 1
    script_src = next(part for part in policies[0].split(";") if "script-src" in part).split()
    assert script_src == ["script-src", "'self'", *sorted([_sha("window.one = 1;"),
                                                           _sha("window.two = 2;")])]
    assert "object-src 'none'" in policies[0]
    assert index.headers["x-content-type-options"] == "nosniff"
    assert model.headers["content-security-policy"].count("sha256") == 0


def test_the_explorer_keeps_the_strict_policy(make_client, tmp_path):
    (tmp_path / "index.html").write_text(PAGE)
    with make_client(docs_dir=tmp_path) as client:
        page = client.get("/")
    assert page.status_code == 200
    assert "sha256" not in page.headers["content-security-policy"]


def test_guide_without_a_slash_leads_to_the_index(make_client, tmp_path):
    (tmp_path / "index.html").write_text(PAGE)
    with make_client(docs_dir=tmp_path) as client:
        answer = client.get("/guide", follow_redirects=False)
    assert answer.status_code == 307 and answer.headers["location"] == "/guide/"


def test_before_the_build_every_guide_path_says_how_to_build_it(make_client, tmp_path):
    with make_client(docs_dir=tmp_path / "missing") as client:
        for path in ("/guide/", "/guide/model.html", "/guide/_static/x.js"):
            answer = client.get(path)
            assert answer.status_code == 404, path
            assert answer.headers["content-type"].startswith("text/html")
            assert "scripts/docs" in answer.text


def test_files_outside_the_built_folder_are_not_served(make_client, tmp_path):
    site = tmp_path / "html"
    site.mkdir()
    (site / "index.html").write_text(PAGE)
    (tmp_path / "secret.txt").write_text("secret")
    with make_client(docs_dir=site) as client:
        for path in ("/guide/../secret.txt", "/guide/%2e%2e/secret.txt", "/guide/nothing.html"):
            answer = client.get(path)
            assert answer.status_code == 404, path
            assert "secret" not in answer.text
