"""Each slider moves the model: the plots it affects change as the model says, the
others stay as they were."""

from __future__ import annotations

import json

import numpy as np
import pytest

from breakaway.dynamics import simulate_breakaway
from breakaway.params import DEFAULTS, FIG3_RATES

from browser_model import assert_plots_match_model, values

pytestmark = pytest.mark.browser

PLOTS = ("stribeck", "hysteresis", "phase", "breakaway")

# parameter -> (key to press on its slider, plots whose data must change with F̂ = avg)
SLIDERS = {
    "Fc": ("ArrowLeft", {"stribeck", "hysteresis", "phase", "breakaway"}),
    "Fs": ("PageUp", {"stribeck", "hysteresis", "phase", "breakaway"}),
    # the loop is driven at a peak speed of 0.1·V, so g(v) along it does not depend on V
    "V": ("PageDown", {"stribeck", "breakaway"}),
    "delta": ("PageUp", {"stribeck", "hysteresis", "breakaway"}),
    "sigma": ("End", {"stribeck", "hysteresis", "breakaway"}),
    "k": ("PageUp", {"phase", "breakaway"}),
    "s": ("PageUp", {"hysteresis", "phase", "breakaway"}),
    "z_ba": ("PageDown", {"phase", "breakaway"}),
}

LABELS = {"Fc": "Fc [N]", "Fs": "Fs [N]", "V": "V [m/s]", "delta": "δ (delta)",
          "sigma": "σ (sigma) [N·s/m]", "k": "k [N/s]", "s": "s [1/m]", "z_ba": "z* (z_ba)",
          "m": "m [kg]"}


def snapshot(explorer):
    """The model's curves on each plot; the simulated ramp's path in the phase plot
    follows every parameter of the simulation (m too) and arrives on its own time."""
    return {plot: {name: trace for name, trace in explorer.traces(plot).items()
                   if name != "simulation"} for plot in PLOTS}


def differs(before: dict, after: dict, rtol: float = 1e-6) -> bool:
    """Whether a plot's traces differ beyond round-off (one float32 step is ~1e-7)."""
    if before.keys() != after.keys():
        return True
    for name, trace in before.items():
        other = after[name]
        for axis in ("x", "y"):
            a, b = values(trace[axis]), values(other[axis])
            if a.shape != b.shape or not np.allclose(a, b, rtol=rtol, atol=0, equal_nan=True):
                return True
    return False


@pytest.mark.parametrize("name", list(SLIDERS))
def test_slider_redraws_the_plots_as_the_model_says(explorer, name):
    key, affected = SLIDERS[name]
    explorer.open("?sim=0")
    before = snapshot(explorer)
    frames = explorer.frames()
    slider = explorer.page.get_by_label(f"{LABELS[name]} slider", exact=True)
    slider.focus()
    slider.press(key)
    explorer.ready()
    state = explorer.state()
    assert state[name] != DEFAULTS[name]
    # the number box beside the slider shows the new value
    box = explorer.page.get_by_label(LABELS[name], exact=True)
    assert float(box.input_value()) == state[name]
    assert explorer.frames() > frames
    assert_plots_match_model(explorer, state)
    after = snapshot(explorer)
    changed = {plot for plot in PLOTS if differs(before[plot], after[plot])}
    assert changed == affected


def test_mass_slider_moves_only_the_simulated_points(explorer):
    explorer.open("?sim=1")
    explorer.sim_ready()
    before = snapshot(explorer)
    asked = []
    explorer.page.on("request", lambda r: asked.append(r.url.rsplit("/", 1)[-1]))
    ramps = explorer.page.locator("#plots").get_attribute("data-ramp-frame")
    slider = explorer.page.get_by_label("m [kg] slider", exact=True)
    slider.focus()
    slider.press("PageUp")
    explorer.ready()
    explorer.sim_ready()
    explorer.page.evaluate("window.breakaway.rampReady()")
    state = explorer.state()
    assert state["m"] > DEFAULTS["m"]
    # the quasi-static frame does not use m: no new frame is asked for, the simulated
    # break-away points are; the short ramp run is made in the page (rampmodel.js)
    assert "explore" not in asked and "simulate" in asked and "ramp" not in asked
    assert int(explorer.page.locator("#plots").get_attribute("data-ramp-frame")) == int(ramps) + 1
    after = snapshot(explorer)
    for plot in ("stribeck", "hysteresis", "phase"):
        assert after[plot] == before[plot]
    curves = [f"F̂ = {name}" for name in ("Fc", "Fs", "avg", "self")]
    assert [after["breakaway"][c] for c in curves] == [before["breakaway"][c] for c in curves]
    simulated = after["breakaway"]["ramp sim.: u(t_ba)"]
    assert simulated["x"] == list(FIG3_RATES)
    p = {n: state[n] for n in ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba")}
    expected = simulate_breakaway(FIG3_RATES, **p, max_steps=1_000_000)
    np.testing.assert_allclose(values(simulated["y"]), expected.u_ba, rtol=1e-12)
    np.testing.assert_allclose(values(after["breakaway"]["ramp sim.: F(t_ba)"]["y"]),
                               expected.F_ba, rtol=1e-12)
    assert simulated != before["breakaway"]["ramp sim.: u(t_ba)"]


def test_typing_in_a_number_box_moves_its_slider_and_the_plots(explorer):
    explorer.open("?sim=0")
    box = explorer.page.get_by_label("Fs [N]", exact=True)
    box.fill("2.25")
    explorer.ready()
    assert explorer.state()["Fs"] == 2.25
    slider = explorer.page.get_by_label("Fs [N] slider", exact=True)
    before = int(slider.input_value())
    assert before > 0
    assert_plots_match_model(explorer)
    stribeck = explorer.traces("stribeck")["Fss(v)"]
    # just right of v = 0 the curve starts near Fs
    first_positive = next(F for v, F in zip(stribeck["x"], stribeck["y"]) if v > 0)
    assert 2.0 < first_positive <= 2.25


def test_f_hat_choice_redraws_phase_and_breakaway(explorer):
    explorer.open("?sim=0")
    before = snapshot(explorer)
    explorer.page.get_by_label("F̂ (F_hat)", exact=True).select_option("self")
    explorer.ready()
    assert explorer.state()["F_hat"] == "self"
    assert_plots_match_model(explorer)
    after = snapshot(explorer)
    assert after["stribeck"] == before["stribeck"] and after["hysteresis"] == before["hysteresis"]
    assert after["phase"] != before["phase"]
    assert after["breakaway"]["F̂ = self"] == before["breakaway"]["F̂ = self"]
    assert after["breakaway"]["current k = 1"] != before["breakaway"]["current k = 1"]


def explore_requests(page) -> list[str]:
    """Collects the /api/explore requests the page sends from now on (their bodies)."""
    sent: list[str] = []
    page.on("request", lambda r: r.url.endswith("/api/explore") and sent.append(r.post_data))
    return sent


def test_a_click_on_the_slider_asks_for_its_frame_once(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("k [N/s] slider", exact=True)
    slider.focus()
    slider.press("ArrowRight")
    explorer.ready()
    sent = explore_requests(page)
    box = slider.bounding_box()
    page.mouse.click(box["x"] + box["width"] * 0.8, box["y"] + box["height"] / 2)
    explorer.ready()
    page.wait_for_timeout(300)
    assert len(sent) == 1  # the clicked position's frame, asked for once it is released
    assert explorer.state()["k"] == json.loads(sent[0])["k"]
    assert_plots_match_model(explorer)


def test_arrow_steps_of_the_mass_ask_for_no_frame(explorer):
    # the quasi-static curves do not use m: neither its step nor the next one needs a frame
    explorer.open("?sim=0")
    page = explorer.page
    sent = explore_requests(page)
    slider = page.get_by_label("m [kg] slider", exact=True)
    slider.focus()
    for _ in range(2):
        slider.press("ArrowRight")
        explorer.ready()
    page.wait_for_timeout(300)
    assert explorer.state()["m"] > DEFAULTS["m"]
    assert sent == []
