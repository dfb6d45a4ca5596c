"""The documentation as `breakaway serve` serves it under /guide/: its pages run their
scripts under the server's policy (each page's inline scripts allowed by hash), so the
search and the light/dark switch work, with no console error and nothing from outside;
and every link of the explorer into the guide leads to a real section."""

from __future__ import annotations

import pytest
from playwright.sync_api import expect

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


def test_the_explorers_links_into_the_guide_lead_to_real_sections(context, guide_url,
                                                                   built_docs):
    html, _ = built_docs
    problems: list[str] = []
    page = _page(context, problems)
    page.goto(guide_url.removesuffix("/guide") + "/")
    page.evaluate("window.breakaway.ready()")
    links = page.eval_on_selector_all('a[href^="/guide/"]',
                                      "links => links.map((a) => a.getAttribute('href'))")
    assert "/guide/" in links  # the header
    glossary = page.eval_on_selector_all('#glossary a[href^="/guide/"]', "links => links.length")
    assert glossary >= 8
    tour = page.evaluate("import('/js/teaching/teach.js').then((m) => "
                         "m.TOUR.map((step) => '/guide/' + m.TOUR_DOCS[step.plot].href))")
    for href in set(links + tour):
        path, _, anchor = href.removeprefix("/guide/").partition("#")
        target = html / (path or "index.html")
        assert target.is_file(), href
        assert not anchor or f'id="{anchor}"' in target.read_text(encoding="utf-8"), href
    page.get_by_role("button", name="Start the tour").click()
    # the step's sweep rewrites the status line above the tour as its curves arrive,
    # which moves the link down (on a loaded machine, between the click's aim and the
    # click): a person follows it once the curves are drawn
    expect(page.get_by_role("button", name="Clear sweep")).to_be_enabled()
    page.evaluate("window.breakaway.ready()")
    more = page.locator("#tour-doc a")
    assert more.inner_text() == "More in the documentation: the Stribeck curve (E2)"
    more.click()
    page.wait_for_url("**/guide/model.html#steady-state-the-stribeck-curve-e2")
    page.close()
    assert problems == []
