"""Inline errors, the URL round trip, history, presets and reset."""

from __future__ import annotations

from urllib.parse import parse_qs, urlparse

import numpy as np
import pytest

from breakaway.params import DEFAULTS, PRESET_DESCRIPTIONS, PRESETS

from browser_model import assert_plots_match_model, wait_ready

pytestmark = pytest.mark.browser

PLOTS = ("stribeck", "hysteresis", "phase", "breakaway")


def count_explore_requests(page) -> list:
    seen = []
    page.on("request", lambda request: "/api/explore" in request.url and seen.append(request))
    return seen


@pytest.mark.parametrize(("label", "text", "field", "message"), [
    ("Fc [N]", "abc", "Fc", "Fc must be a number"),
    ("δ (delta)", "0", "delta", "|δ| ≥ 0.05"),
    ("z* (z_ba)", "1", "z_ba", "z* must be in (0, 1)"),
    ("σ (sigma) [N·s/m]", "-0.1", "sigma", "σ must be ≥ 0"),
    ("k [N/s]", "0", "k", "k must be > 0"),
])
def test_invalid_value_shows_inline_error_and_is_not_sent(explorer, label, text, field, message):
    explorer.open("?sim=0")
    page = explorer.page
    before = {plot: explorer.traces(plot) for plot in PLOTS}
    requests = count_explore_requests(page)
    box = page.get_by_label(label, exact=True)
    box.fill(text)
    explorer.ready()
    error = page.locator(f"#{field}-error")
    assert error.is_visible()
    assert message in error.inner_text()
    assert box.get_attribute("aria-invalid") == "true"
    assert page.locator("#plots").get_attribute("data-valid") == "false"
    assert requests == []
    assert {plot: explorer.traces(plot) for plot in PLOTS} == before
    # a valid value clears the error; it is the state the plots already show, so the
    # page asks for no new frame
    frames = explorer.frames()
    box.fill(str(DEFAULTS[field]))
    explorer.ready()
    assert not error.is_visible()
    assert box.get_attribute("aria-invalid") == "false"
    assert page.locator("#plots").get_attribute("data-valid") == "true"
    assert explorer.frames() == frames + 1
    assert requests == []
    assert_plots_match_model(explorer)


def test_fs_and_fc_stay_coupled_and_the_url_stays_valid(explorer):
    explorer.open("?sim=0&Fc=1&Fs=1")
    page = explorer.page
    slider = page.get_by_label("Fs [N] slider", exact=True)
    slider.focus()
    slider.press("ArrowLeft")
    explorer.ready()
    state = explorer.state()
    # Fs moved below Fc: Fc follows, nothing freezes, no error
    assert state["Fs"] < 1 and state["Fc"] == state["Fs"]
    assert not page.locator("#Fs-error").is_visible()
    assert page.locator("#plots").get_attribute("data-valid") == "true"
    assert float(page.get_by_label("Fc [N]", exact=True).input_value()) == state["Fc"]
    # typing Fc above Fs: Fs follows
    box = page.get_by_label("Fc [N]", exact=True)
    box.fill("3")
    box.press("Enter")
    explorer.ready()
    state = explorer.state()
    assert state["Fc"] == 3 and state["Fs"] == 3
    query = parse_qs(urlparse(page.url).query)
    assert query["Fs"] == ["3"] and query["Fc"] == ["3"]
    # an invalid value never reaches the URL or the history
    before, length = page.url, page.evaluate("history.length")
    box.fill("abc")
    box.press("Enter")
    explorer.ready()
    assert page.locator("#Fc-error").is_visible()
    assert page.url == before and page.evaluate("history.length") == length


def test_plotly_toolbar_offers_no_cloud_and_stays_out_of_the_tab_order(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    titles = page.evaluate("[...document.querySelectorAll('#plots .modebar-btn')]"
                           ".map(b => b.getAttribute('data-title') || '')")
    assert titles and not [t for t in titles if "cloud" in t.lower() or "chart studio" in t.lower()]
    assert page.locator("#plots .modebar-btn").count() > 0
    assert page.evaluate("[...document.querySelectorAll('#plots .modebar-btn')]"
                         ".every(b => b.tabIndex === -1)")
    assert page.locator(".plotlyjsicon").count() == 0  # no Plotly logo
    assert not page.locator("#loading").is_visible()


def test_url_round_trip_restores_the_view(explorer, browser, server_url):
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_label("Fc [N]", exact=True).fill("0.8")
    page.get_by_label("Fc [N]", exact=True).press("Enter")
    page.get_by_label("V [m/s]", exact=True).fill("12.5")
    page.get_by_label("V [m/s]", exact=True).press("Tab")
    page.get_by_label("F̂ (F_hat)", exact=True).select_option("Fs")
    explorer.ready()
    wait_ready(page, "rampReady")  # the phase plot's simulated path of this state
    query = parse_qs(urlparse(page.url).query)
    assert query["Fc"] == ["0.8"] and query["V"] == ["12.5"] and query["F_hat"] == ["Fs"]
    state = explorer.state()
    shown = {plot: explorer.traces(plot) for plot in PLOTS}

    context = browser.new_context(viewport={"width": 1280, "height": 800})
    try:
        other = context.new_page()
        other.goto(page.url)
        wait_ready(other, "rampReady")
        assert other.evaluate("window.breakaway.state()") == state
        assert other.get_by_label("V [m/s]", exact=True).input_value() == "12.5"
        assert other.get_by_label("F̂ (F_hat)", exact=True).input_value() == "Fs"
        for plot in PLOTS:
            traces = other.evaluate(
                """(id) => document.getElementById('plot-' + id).data.map(t => (
                    {name: t.name, x: Array.from(t.x), y: Array.from(t.y),
                     customdata: t.customdata ? Array.from(t.customdata) : null}))""", plot)
            assert {t["name"]: t for t in traces} == shown[plot]
    finally:
        context.close()


def test_back_and_forward_walk_the_history(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    k_box = page.get_by_label("k [N/s]", exact=True)
    k_box.fill("5")
    k_box.press("Enter")
    explorer.ready()
    k_box.fill("12")
    k_box.press("Enter")
    explorer.ready()
    assert explorer.state()["k"] == 12
    page.go_back()
    explorer.ready()
    assert explorer.state()["k"] == 5
    assert k_box.input_value() == "5"
    assert_plots_match_model(explorer)
    page.go_back()
    explorer.ready()
    assert explorer.state()["k"] == DEFAULTS["k"]
    page.go_forward()
    explorer.ready()
    assert explorer.state()["k"] == 5
    assert_plots_match_model(explorer)


def test_invalid_value_in_the_url_is_shown_not_sent(explorer):
    explorer.open("?sim=0&Fs=0.2")
    assert explorer.page.locator("#Fs-error").is_visible()
    assert explorer.page.get_by_label("Fs [N]", exact=True).input_value() == "0.2"
    assert explorer.frames() == 0


@pytest.mark.parametrize("name", ["lugre-1995", "sharp-stribeck", "strengthening"])
def test_preset_loads(explorer, name):
    explorer.open("?sim=0")
    explorer.page.get_by_label("Preset", exact=True).select_option(name)
    explorer.ready()
    state = explorer.state()
    for key, value in PRESETS[name].items():
        assert state[key] == value
    assert explorer.page.locator("#preset-description").inner_text() == PRESET_DESCRIPTIONS[name]
    assert parse_qs(urlparse(explorer.page.url).query)["V"] == [str(PRESETS[name]["V"])
                                                              .removesuffix(".0")]
    assert_plots_match_model(explorer)


def test_reset_returns_to_the_defaults(explorer):
    explorer.open("?sim=0&Fc=0.5&Fs=3&k=7&F_hat=self")
    assert explorer.state()["Fs"] == 3
    explorer.page.get_by_role("button", name="Reset", exact=True).click()
    explorer.ready()
    state = explorer.state()
    for key, value in DEFAULTS.items():
        assert state[key] == value
    assert explorer.page.get_by_label("Preset", exact=True).input_value() == "fig5"
    assert_plots_match_model(explorer)


def test_a_loading_line_shows_until_the_first_frame_is_drawn(explorer, server_url):
    page = explorer.page
    held = []
    page.route("**/api/explore", lambda route: held.append(route))  # held until released
    page.goto(f"{server_url}/?sim=0")
    for _ in range(200):
        if held:
            break
        page.wait_for_timeout(25)
    assert held, "the page asked for no frame"
    loading = page.locator("#loading")
    assert loading.is_visible() and "Loading" in loading.inner_text()
    assert page.locator("#plots").get_attribute("data-ready") == "false"
    assert page.locator("#plots").get_attribute("aria-busy") == "true"
    held[0].continue_()
    explorer.ready()
    page.unroute("**/api/explore")
    assert not loading.is_visible()
    assert page.locator("#plots").get_attribute("aria-busy") == "false"


@pytest.mark.parametrize("granted", [True, False])
def test_copy_link_says_so_next_to_the_button(explorer, granted):
    explorer.open("?sim=0&Fc=0.8")
    page = explorer.page
    if granted:
        page.context.grant_permissions(["clipboard-read", "clipboard-write"])
    else:
        page.context.clear_permissions()
        page.evaluate("() => { navigator.clipboard.writeText = () => Promise.reject(new Error('denied')); }")
    button = page.get_by_role("button", name="Copy link")
    button.click()
    status = page.locator("#copy-status")
    status.wait_for(state="visible")
    expected = "Link copied." if granted else f"Copy this link: {page.url}"
    assert status.inner_text() == expected
    if granted:
        assert page.evaluate("navigator.clipboard.readText()") == page.url
    # within the viewport and right under the button
    near, shown = button.bounding_box(), status.bounding_box()
    assert 0 <= shown["y"] - (near["y"] + near["height"]) < 40
    assert shown["y"] + shown["height"] <= page.viewport_size["height"]
    page.context.clear_permissions()


def test_the_delta_slider_offers_only_valid_values(explorer):
    # δ = 0 is no model (|δ| ≥ 0.05): the slider steps from −0.05 to 0.05, as a drag over
    # every position and the arrow keys across zero show
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("δ (delta) slider", exact=True)
    offered = page.evaluate("""() => {
      const range = document.getElementById('delta-range');
      const out = [];
      for (let p = Number(range.min); p <= Number(range.max); p++) {
        range.value = String(p);
        range.dispatchEvent(new Event('input', {bubbles: true}));
        out.push([window.breakaway.state().delta,
                  document.getElementById('delta-error').hidden]);
      }
      return out;
    }""")
    deltas = [delta for delta, _ in offered]
    assert all(hidden for _, hidden in offered)
    assert min(abs(d) for d in deltas) == pytest.approx(0.05)
    assert deltas[0] == -4 and deltas[-1] == 4 and len(set(deltas)) == len(deltas) == 160
    steps = np.diff(deltas)
    assert np.allclose(steps[steps < 0.07], 0.05) and list(np.round(steps[steps >= 0.07], 9)) == [0.1]
    explorer.ready()
    page.get_by_label("δ (delta)", exact=True).fill("-0.1")
    explorer.ready()
    seen = []
    for _ in range(3):
        slider.press("ArrowRight")
        seen.append(explorer.state()["delta"])
    assert seen == [-0.05, 0.05, 0.1]
    explorer.ready()
    assert page.locator("#plots").get_attribute("data-valid") == "true"


def test_a_value_typed_just_after_a_valid_change_leaves_every_view_on_that_change(explorer):
    # the plots keep the last valid state; what was on its way for it (the settled frame,
    # the ramp and its sentence) is drawn, not dropped
    explorer.open("?sim=0&k=2")
    page = explorer.page
    page.get_by_label("k [N/s] slider", exact=True).press("PageUp")
    k = explorer.state()["k"]
    assert k != 2
    page.get_by_label("Fs [N]", exact=True).fill("abc")
    explorer.ready()
    explorer.page.evaluate("window.breakaway.rampReady()")
    assert page.locator("#plots").get_attribute("data-valid") == "false"
    assert page.locator("#Fs-error").is_visible()
    assert explorer.page.evaluate("window.breakaway.viewParams('ramp')")["Fs"] == DEFAULTS["Fs"]
    assert explorer.traces("breakaway")[f"current k = {k:.4g}"]["x"] == [k]
    assert f"At k = {k:.3g} N/s" in page.locator("#ba-explain").inner_text()
