"""Browser tests: the real server (uvicorn, subprocess) and headless Chromium (Playwright).

Chromium: ``BREAKAWAY_CHROMIUM`` if set and non-empty, else ``/usr/bin/chromium`` if it
exists, else Playwright's own browser. A browser that cannot launch FAILS the tests
(never skips them): CI must run them.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from browser_model import wait_ready
from live_server import serve

BROWSER_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                "--disable-component-update", "--disable-sync"]
DESKTOP = {"width": 1280, "height": 800}


def chromium_path() -> str | None:
    chosen = os.environ.get("BREAKAWAY_CHROMIUM", "")
    if chosen:
        return chosen
    if Path("/usr/bin/chromium").exists():
        return "/usr/bin/chromium"
    return None  # Playwright's bundled browser


@pytest.fixture(scope="session")
def server_url():
    with serve() as url:
        yield url


@pytest.fixture(scope="session")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        try:
            browser = playwright.chromium.launch(executable_path=chromium_path(),
                                                 headless=True, args=BROWSER_ARGS)
        except Exception as exc:  # noqa: BLE001 - any launch failure must fail, not skip
            pytest.fail(f"Chromium did not launch ({chromium_path() or 'Playwright default'}): "
                        f"{exc}", pytrace=False)
        yield browser
        browser.close()


#: A fit job's own URL (its status, polled from the moment it is queued).
FIT_JOB = re.compile(r"/api/fit/jobs/([0-9a-f]+)$")


class Explorer:
    """A page of the explorer plus helpers that read what the plots show."""

    def __init__(self, page, base_url):
        self.page = page
        self.base_url = base_url
        self.problems: list[str] = []
        page.on("console", lambda message: message.type == "error"
                and self.problems.append(f"console: {message.text}"))
        page.on("pageerror", lambda error: self.problems.append(f"page error: {error}"))
        #: the fit jobs this page asked about (cancelled when its test ends)
        self.fit_jobs: set[str] = set()
        page.on("request", lambda request: (job := FIT_JOB.search(request.url))
                and self.fit_jobs.add(job.group(1)))

    def open(self, query: str = "") -> "Explorer":
        self.page.goto(f"{self.base_url}/{query}")
        self.ready()
        # the ramp experiment redraws the phase plot (its simulated path) when it arrives
        self.page.evaluate("window.breakaway.rampReady()")
        return self

    def ready(self) -> None:
        wait_ready(self.page)

    def cancel_fits(self) -> None:
        """Cancel the fit jobs this page started: one still running when its test ends
        holds the server's single fit worker, and a later test's fit waits behind it."""
        for job in self.fit_jobs:
            self.page.request.delete(f"{self.base_url}/api/fit/jobs/{job}")

    def sim_ready(self) -> None:
        wait_ready(self.page, "simReady")

    def traces(self, plot: str) -> dict[str, dict]:
        """The plotted traces of ``plot`` by name: {name: {x, y, customdata}}."""
        traces = self.page.evaluate(
            """(id) => document.getElementById('plot-' + id).data.map(t => (
                {name: t.name, x: Array.from(t.x), y: Array.from(t.y),
                 customdata: t.customdata ? Array.from(t.customdata) : null}))""", plot)
        return {trace["name"]: trace for trace in traces}

    def frames(self) -> int:
        return self.page.evaluate("window.breakaway.frames()")

    def state(self) -> dict:
        return self.page.evaluate("window.breakaway.state()")


@pytest.fixture(scope="session")
def context(browser):
    """One browser context for the session: its HTTP cache keeps Plotly (4.8 MB) loaded."""
    context = browser.new_context(viewport=DESKTOP, accept_downloads=True)
    yield context
    context.close()


@pytest.fixture
def explorer(context, server_url):
    page = context.new_page()
    page.set_viewport_size(DESKTOP)
    page.set_default_timeout(20_000)
    explorer = Explorer(page, server_url)
    yield explorer
    explorer.cancel_fits()
    page.close()
    # CSP violations and script errors show up here
    assert explorer.problems == []
