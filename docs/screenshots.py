"""Regenerate the screenshots of the documentation and the README (docs/images/).

    .venv/bin/python docs/screenshots.py

Starts ``breakaway serve`` on a free port, drives headless Chromium with Playwright
(Debian's chromium where it exists, else ``BREAKAWAY_CHROMIUM`` or Playwright's own) and
writes one PNG per view that the explorer and data panel guides show. Run it after a
change to the page, then look at the pictures before committing them.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))
sys.path.insert(0, str(HERE.parent / "tests" / "browser"))

from conftest import BROWSER_ARGS, chromium_path  # noqa: E402  (tests/browser)
from live_server import serve  # noqa: E402

IMAGES = HERE / "images"
LAPTOP = {"width": 1280, "height": 800}
PHONE = {"width": 390, "height": 844}


def settle(page) -> None:
    """Wait until the plots, the simulation and the ramp show the current state."""
    page.evaluate("window.breakaway.ready()")
    page.evaluate("window.breakaway.simReady()")
    page.evaluate("window.breakaway.rampReady()")


def explorer(browser, url: str) -> None:
    page = browser.new_page(viewport=LAPTOP, device_scale_factor=1)
    page.set_default_timeout(120_000)
    page.goto(f"{url}/")
    settle(page)
    page.screenshot(path=IMAGES / "explorer.png")

    page.locator("#card-ramp").scroll_into_view_if_needed()
    page.locator("#card-ramp").screenshot(path=IMAGES / "explorer-ramp.png")

    page.get_by_role("button", name="Show the control loop").click()
    page.evaluate("window.breakaway.loopReady()")
    page.locator("#card-loop").screenshot(path=IMAGES / "explorer-loop.png")

    page.goto(f"{url}/")
    settle(page)
    page.get_by_role("button", name="Start the tour").click()
    settle(page)
    # the step's text and its link into the documentation, with the plots beside them
    page.locator("#tour-doc").scroll_into_view_if_needed()
    page.screenshot(path=IMAGES / "explorer-tour.png")
    page.close()

    phone = browser.new_page(viewport=PHONE, device_scale_factor=2, is_mobile=True,
                             has_touch=True)
    phone.set_default_timeout(120_000)
    phone.goto(f"{url}/")
    settle(phone)
    phone.screenshot(path=IMAGES / "explorer-phone.png")
    phone.close()


def data_panel(browser, url: str) -> None:
    page = browser.new_page(viewport={"width": 1280, "height": 1000}, device_scale_factor=1)
    page.set_default_timeout(300_000)
    page.goto(f"{url}/")
    settle(page)
    panel = page.locator("#data-panel")
    page.get_by_label("Sample", exact=True).select_option("damper")
    page.get_by_role("button", name="Fit", exact=True).click()
    page.evaluate("window.breakaway.fitReady()")
    panel.scroll_into_view_if_needed()
    page.locator("#fit-results").screenshot(path=IMAGES / "data-panel-results.png")

    page.get_by_label("Sample", exact=True).select_option("mystery-a")
    page.get_by_role("button", name="Fit", exact=True).click()
    page.evaluate("window.breakaway.fitReady()")
    panel.screenshot(path=IMAGES / "data-panel-quiz.png")
    page.close()


def main() -> int:
    from playwright.sync_api import sync_playwright

    IMAGES.mkdir(exist_ok=True)
    with serve() as url, sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium_path(), headless=True,
                                             args=BROWSER_ARGS)
        explorer(browser, url)
        data_panel(browser, url)
        browser.close()
    for path in sorted(IMAGES.glob("*.png")):
        print(f"{path.relative_to(HERE.parent)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
