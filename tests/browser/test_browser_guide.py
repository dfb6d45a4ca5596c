"""The documentation as `breakaway serve` serves it under /guide/: its pages run their
scripts under the server's policy (each page's inline scripts allowed by hash), so the
search and the light/dark switch work, with no console error and nothing from outside."""

from __future__ import annotations

import pytest

from conftest import DESKTOP
from live_server import serve


@pytest.fixture(scope="module")
def guide_url(built_docs):
    html, done = built_docs
    assert done.returncode == 0, done.stderr[-2000:]
    with serve(docs_dir=html) as url:
        yield f"{url}/guide"


def _page(context, problems):
    page = context.new_page()
    page.set_viewport_size(DESKTOP)
    page.on("console", lambda message: message.type == "error"
            and problems.append(f"console: {message.text}"))
    page.on("pageerror", lambda error: problems.append(f"page error: {error}"))
    page.on("request", lambda request: request.url.startswith("http://127.0.0.1")
            or problems.append(f"outside request: {request.url}"))
    return page


def test_the_guide_searches_under_the_servers_policy(context, guide_url):
    problems: list[str] = []
    page = _page(context, problems)
    page.goto(f"{guide_url}/search.html?q=hysteresis")
    results = page.locator("#search-results li")
    results.first.wait_for(timeout=20_000)
    titles = " ".join(results.all_inner_texts())
    assert "The friction model" in titles
    page.close()
    assert problems == []


def test_the_theme_switch_and_the_links_back_to_the_explorer(context, guide_url):
    problems: list[str] = []
    page = _page(context, problems)
    page.goto(f"{guide_url}/model.html", wait_until="load")
    assert page.title().startswith("The friction model")
    page.get_by_role("button", name="Color mode").first.click()
    page.get_by_role("button", name="Dark").first.click()
    page.wait_for_function("document.documentElement.dataset.theme === 'dark'", timeout=10_000)
    page.get_by_role("link", name="Explorer", exact=True).filter(visible=True).click()
    page.wait_for_url(lambda url: "/guide" not in url)
    page.get_by_label("Fs [N]", exact=True).wait_for()
    page.close()
    assert problems == []
