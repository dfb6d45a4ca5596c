"""Redraw (one request in flight, stale ones aborted), the simulation points,
keyboard use, and the layout at 1280×800 and at phone width."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.dynamics import simulate_breakaway, simulate_lugre_breakaway
from breakaway.params import DEFAULTS, FIG3_RATES

from browser_model import assert_plots_match_model, values

pytestmark = pytest.mark.browser

COUNT_FETCHES = """
(() => {
  // an explore request is in flight from fetch() until it settles or is aborted
  const original = window.fetch;
  window.__explore = {inFlight: 0, maxInFlight: 0, started: 0, finished: 0, aborted: 0};
  window.fetch = async (url, options) => {
    if (!String(url).includes('/api/explore')) return original(url, options);
    const stats = window.__explore;
    let open = true;
    const close = () => { if (open) { open = false; stats.inFlight -= 1; } };
    stats.started += 1; stats.inFlight += 1;
    stats.maxInFlight = Math.max(stats.maxInFlight, stats.inFlight);
    options?.signal?.addEventListener('abort', () => { stats.aborted += 1; close(); });
    try {
      const response = await original(url, options);
      stats.finished += 1;
      return response;
    } finally {
      close();
    }
  };
})();
"""


def test_one_request_in_flight_and_stale_ones_aborted(explorer):
    explorer.page.add_init_script(COUNT_FETCHES)
    explorer.open("?sim=0")
    # 40 slider inputs in one task, as fast as a drag can produce them: drawn live, and
    # the server asked once the hand rests
    explorer.page.evaluate("""() => {
        const slider = document.getElementById('Fs-range');
        for (let i = 0; i < 40; i++) {
            slider.value = String(520 + i * 5);
            slider.dispatchEvent(new Event('input', {bubbles: true}));
        }
    }""")
    explorer.ready()
    stats = explorer.page.evaluate("window.__explore")
    assert stats["maxInFlight"] == 1
    assert stats["started"] == 2  # the first frame, and the state the hand stopped on
    # a slider released asks at once; released again before the answer came, the first
    # request is for a state left, and aborted
    explorer.page.evaluate("""() => {
        const slider = document.getElementById('Fs-range');
        for (const position of [700, 720]) {
            slider.value = String(position);
            slider.dispatchEvent(new Event('input', {bubbles: true}));
            slider.dispatchEvent(new Event('change', {bubbles: true}));
        }
    }""")
    explorer.ready()
    stats = explorer.page.evaluate("window.__explore")
    assert stats["maxInFlight"] == 1
    assert stats["started"] == 4 and stats["aborted"] == 1
    state = explorer.state()
    assert state["Fs"] == float(explorer.page.get_by_label("Fs [N]", exact=True).input_value())
    assert_plots_match_model(explorer, state)


def test_simulated_break_away_points_follow_the_model(explorer):
    explorer.open("?sim=1&lugre=0")
    explorer.sim_ready()
    traces = explorer.traces("breakaway")
    p = {name: DEFAULTS[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba")}
    expected = simulate_breakaway(FIG3_RATES, **p, max_steps=1_000_000)
    assert traces["ramp sim.: u(t_ba)"]["x"] == list(FIG3_RATES)
    np.testing.assert_allclose(values(traces["ramp sim.: u(t_ba)"]["y"]), expected.u_ba,
                               rtol=1e-12)
    np.testing.assert_allclose(values(traces["ramp sim.: F(t_ba)"]["y"]), expected.F_ba,
                               rtol=1e-12)
    assert "LuGre 1995: max F" not in traces
    status = explorer.page.locator("#sim-status").inner_text()
    assert status.startswith("Simulated 15 ramps")


def test_lugre_toggle(explorer):
    explorer.open("?sim=0")
    explorer.page.get_by_label("Show LuGre (1995)").check()
    explorer.sim_ready()
    traces = explorer.traces("breakaway")
    expected = simulate_lugre_breakaway(FIG3_RATES, max_steps=1_000_000)
    lugre = traces["LuGre 1995: max F"]
    assert lugre["x"] == list(FIG3_RATES)
    np.testing.assert_allclose(values(lugre["y"]), expected.F_ba, rtol=1e-12)
    assert "lugre=1" in explorer.page.url
    explorer.page.get_by_label("Show LuGre (1995)").uncheck()
    explorer.ready()
    explorer.page.wait_for_function(
        "!document.getElementById('plot-breakaway').data.some(t => t.name.startsWith('LuGre'))")


def test_simulate_now_button_runs_with_auto_simulation_off(explorer):
    explorer.open("?sim=0")
    assert "ramp sim.: u(t_ba)" not in explorer.traces("breakaway")
    explorer.page.get_by_role("button", name="Simulate now").click()
    explorer.sim_ready()
    assert len(explorer.traces("breakaway")["ramp sim.: u(t_ba)"]["x"]) == len(FIG3_RATES)


def test_keyboard_reaches_and_moves_a_slider(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    page.locator("body").focus()
    for _ in range(40):
        page.keyboard.press("Tab")
        focused = page.evaluate("document.activeElement.id")
        if focused == "k-range":
            break
    else:
        pytest.fail("Tab never reached the k slider")
    frames = explorer.frames()
    page.keyboard.press("ArrowRight")
    explorer.ready()
    assert explorer.state()["k"] > DEFAULTS["k"]
    assert explorer.frames() == frames + 1
    page.keyboard.press("End")
    explorer.ready()
    assert explorer.state()["k"] == 30
    assert_plots_match_model(explorer)


def _layout(page):
    return page.evaluate("""() => {
        const box = (el) => { const r = el.getBoundingClientRect();
            return {left: r.left, right: r.right, top: r.top, width: r.width, height: r.height}; };
        return {
            scrollWidth: document.documentElement.scrollWidth,
            innerWidth: window.innerWidth,
            plots: [...document.querySelectorAll('.plot')].map(box),
            controls: box(document.getElementById('controls')),
        };
    }""")


def test_layout_at_1280_by_800(explorer):
    explorer.open("?sim=0")
    layout = _layout(explorer.page)
    assert layout["scrollWidth"] <= layout["innerWidth"]
    assert len(layout["plots"]) == 8
    for plot in layout["plots"]:
        assert plot["width"] >= 350 and plot["height"] >= 180
        assert 0 <= plot["left"] and plot["right"] <= 1280
    # the four model plots sit in two columns beside the controls, the ramp below them
    # across both, and below it the control loop's three, stacked on one time axis
    four, ramp, loop = layout["plots"][:4], layout["plots"][4], layout["plots"][5:]
    assert all(plot["height"] >= 240 for plot in four + [ramp])
    assert len({round(plot["left"]) for plot in four}) == 2
    assert layout["controls"]["right"] <= min(plot["left"] for plot in layout["plots"])
    assert ramp["top"] >= max(plot["top"] + plot["height"] for plot in four)
    assert ramp["width"] >= 1.9 * four[0]["width"]
    assert loop[0]["top"] >= ramp["top"] + ramp["height"]
    assert all(plot["width"] == ramp["width"] and plot["left"] == ramp["left"] for plot in loop)
    assert loop[0]["top"] < loop[1]["top"] < loop[2]["top"]
    # what comes below the plots stays clear of the sticky controls, scrolled to
    for selector in ("#glossary summary", "#data-panel"):
        element = explorer.page.locator(selector)
        element.scroll_into_view_if_needed()
        box = element.bounding_box()
        controls = explorer.page.locator("#controls").bounding_box()
        assert box["x"] >= controls["x"] + controls["width"], selector
        assert explorer.page.evaluate(
            "(s) => { const r = document.querySelector(s).getBoundingClientRect();"
            " return document.elementFromPoint(r.left + 5, r.top + r.height / 2)"
            ".closest(s) !== null; }", selector)


def test_phone_width(explorer):
    explorer.page.set_viewport_size({"width": 390, "height": 844})
    explorer.open("?sim=0")
    layout = _layout(explorer.page)
    assert layout["scrollWidth"] <= layout["innerWidth"]
    for plot in layout["plots"]:
        # one plot in view at a time, each the screen's width (phone.js, the plot strip)
        assert 300 <= plot["width"] <= 390
    box = explorer.page.get_by_label("Fs [N]", exact=True)
    box.scroll_into_view_if_needed()
    box.fill("2")
    explorer.ready()
    assert explorer.state()["Fs"] == 2
    assert_plots_match_model(explorer)
