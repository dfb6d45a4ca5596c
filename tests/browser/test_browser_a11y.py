"""Accessibility: axe-core on the page (the explorer and the data panel below it, which
is where the second tab was), in light, dark and presentation styles, with and without a
report shown; and the keyboard path through the controls."""

from __future__ import annotations

import pytest
from axe_playwright_python.sync_playwright import Axe

from breakaway.identify.samples import SAMPLES

from browser_model import until

pytestmark = pytest.mark.browser

SERIOUS = {"serious", "critical"}


def serious_violations(page) -> list[str]:
    results = Axe().run(page)
    return [f"{v['id']} ({v['impact']}): {v['help']} — "
            + "; ".join(node["target"][0] if isinstance(node["target"][0], str)
                        else str(node["target"]) for node in v["nodes"][:5])
            for v in results.response["violations"] if v["impact"] in SERIOUS]


@pytest.mark.parametrize("scheme,query", [("light", "?sim=0"), ("dark", "?sim=0"),
                                          ("light", "?sim=0&present=1")])
def test_axe_finds_nothing_serious(explorer, scheme, query):
    explorer.page.emulate_media(color_scheme=scheme)
    explorer.open(query)
    assert serious_violations(explorer.page) == []


@pytest.mark.parametrize("scheme", ["light", "dark"])
def test_axe_finds_nothing_serious_with_a_report_shown(explorer, scheme):
    explorer.page.emulate_media(color_scheme=scheme)
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_label("Sample", exact=True).select_option(label=SAMPLES["mystery-e"].title)
    page.get_by_role("button", name="Fit", exact=True).click()
    page.wait_for_selector('[data-state="done"]', timeout=60_000)
    page.get_by_label("Your guess", exact=True).select_option("none")
    page.get_by_role("button", name="Reveal the diagnosis").click()
    assert page.locator("#fit-results").is_visible()
    assert serious_violations(page) == []


def test_the_sliders_answer_the_keyboard_and_show_focus(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("Fc [N] slider")
    slider.focus()
    before = explorer.state()["Fc"]
    frames = explorer.frames()
    page.keyboard.press("ArrowRight")
    explorer.ready()
    assert explorer.state()["Fc"] > before
    assert explorer.frames() == frames + 1
    outline = page.evaluate(
        "() => { const s = getComputedStyle(document.activeElement);"
        " return [s.outlineStyle, parseFloat(s.outlineWidth)]; }")
    assert outline[0] != "none" and outline[1] >= 2


def test_axe_finds_nothing_serious_with_live_frames_drawn(explorer):
    # an arrow step draws a live frame on a canvas in each plot before Plotly settles
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("σ (sigma) [N·s/m] slider", exact=True)
    slider.focus()
    frames = explorer.frames()
    slider.press("ArrowRight")
    until(page, f"window.breakaway.frames() > {frames}")
    live = page.evaluate("""() => [...document.querySelectorAll('#plots canvas.live-layer')].map(
        (c) => [c.closest('.plot').id, c.getAttribute('aria-hidden'),
                getComputedStyle(c).pointerEvents])""")
    model = {f"plot-{p}" for p in ("stribeck", "hysteresis", "phase", "breakaway")}
    # the control loop follows the friction live too, once its answer is in
    loop = {f"plot-{p}" for p in ("loop-position", "loop-error", "loop-force")}
    assert model <= {plot for plot, _, _ in live} <= model | loop
    assert all(hidden == "true" and events == "none" for _, hidden, events in live)
    explorer.ready()
    assert serious_violations(page) == []
