"""The explorer on a phone (390×844): the plot being explored stays in view while its
slider moves, one plot at a time, no horizontal scroll, and every control a finger can
hit (44 px)."""

from __future__ import annotations

import pytest

from browser_model import assert_plots_match_model, until

pytestmark = pytest.mark.browser

PHONE = {"width": 390, "height": 844}

#: Slider label -> the plots it moves (tests/browser/test_browser_sliders.py), the ramp
#: experiment following every parameter.
MOVES = {
    "Fc [N]": {"stribeck", "hysteresis", "phase", "breakaway"},
    "V [m/s]": {"stribeck", "breakaway"},
    "σ (sigma) [N·s/m]": {"stribeck", "hysteresis", "breakaway"},
    "k [N/s]": {"phase", "breakaway"},
    "s [1/m]": {"hysteresis", "phase", "breakaway"},
    "z* (z_ba)": {"phase", "breakaway"},
    "m [kg]": {"ramp"},
}

BOX = """(selector) => { const r = document.querySelector(selector).getBoundingClientRect();
    return {top: r.top, bottom: r.bottom, left: r.left, right: r.right}; }"""


def in_view(page) -> str:
    return page.locator("#plots").get_attribute("data-in-view")


@pytest.fixture
def phone(explorer):
    explorer.page.set_viewport_size(PHONE)
    explorer.open("?sim=0")
    return explorer


@pytest.mark.parametrize("label", list(MOVES))
def test_the_plot_a_slider_moves_stays_in_view_while_it_moves(phone, label):
    page = phone.page
    slider = page.get_by_label(f"{label} slider", exact=True)
    slider.focus()  # the browser scrolls it into view, below the plots
    until(page, "document.getElementById('plots').dataset.inView !== undefined")
    plot = in_view(page)
    assert plot in MOVES[label] | {"ramp"}
    frames = phone.frames()
    slider.press("PageUp")
    until(page, f"window.breakaway.frames() > {frames}")
    card = page.evaluate(BOX, f"#card-{plot}")
    graph = page.evaluate(BOX, f"#plot-{plot}")
    control = slider.bounding_box()
    # the plot wholly on the screen, the slider below it, neither covering the other
    assert 0 <= card["left"] and card["right"] <= PHONE["width"]
    assert 0 <= graph["top"] and graph["bottom"] <= control["y"]
    assert control["y"] + control["height"] <= PHONE["height"]
    hit = page.evaluate("""([x, y]) => document.elementFromPoint(x, y).closest('input')?.id""",
                        [control["x"] + control["width"] / 2, control["y"] + control["height"] / 2])
    assert hit == slider.get_attribute("id")
    assert page.evaluate("document.documentElement.scrollWidth") <= PHONE["width"]
    phone.ready()
    assert_plots_match_model(phone)


def test_the_plot_in_view_is_picked_or_swiped(phone):
    page = phone.page
    assert in_view(page) == "stribeck"
    page.get_by_role("button", name="Phase", exact=True).click()
    until(page, "document.getElementById('plots').dataset.inView === 'phase'")
    until(page, "Math.abs(document.getElementById('card-phase').getBoundingClientRect().left"
                " - document.querySelector('.plot-track').getBoundingClientRect().left) < 2")
    assert page.get_by_role("button", name="Phase", exact=True).get_attribute("aria-pressed") == "true"
    # a swipe to the next plot: the strip scrolls by one screen width
    page.evaluate("""() => { const strip = document.querySelector('.plot-track');
        strip.scrollBy({left: strip.clientWidth, behavior: 'instant'}); }""")
    until(page, "document.getElementById('plots').dataset.inView === 'breakaway'")
    # the sentence about the ramp shows with the ramp only
    assert not page.locator("#ba-explain").is_visible()
    page.get_by_role("button", name="Ramp", exact=True).click()
    until(page, "document.getElementById('plots').dataset.inView === 'ramp'")
    page.evaluate("window.breakaway.rampReady()")
    assert page.locator("#ba-explain").is_visible()


#: Every control on the page a finger may use, with the box it answers to (a check box
#: answers through its label too), outside Plotly's own graphs.
TARGETS = """() => {
  const out = [];
  const selector = 'button, select, input, summary, [role="tab"]';
  for (const element of document.querySelectorAll(selector)) {
    if (element.closest('.js-plotly-plot, .skip-link')) continue;
    const style = getComputedStyle(element);
    if (!element.getClientRects().length || style.visibility === 'hidden') continue;
    const target = element.type === 'checkbox' ? element.closest('.check') : element;
    const r = target.getBoundingClientRect();
    out.push({what: element.id || element.textContent.trim() || element.name, width: r.width, height: r.height});
  }
  return out;
}"""


def test_every_control_is_a_finger_wide(phone):
    targets = phone.page.evaluate(TARGETS)
    assert len(targets) >= 40
    small = [t for t in targets if t["width"] < 44 or t["height"] < 44]
    assert small == []
