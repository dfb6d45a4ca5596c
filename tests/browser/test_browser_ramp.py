"""The ramp experiment on screen: its plot redraws with k and m, the simulated path in
the phase plot, the explanation's numbers against /api/ramp, play, and the glossary."""

from __future__ import annotations

import json
import re
import urllib.request

import pytest

from browser_model import until

pytestmark = pytest.mark.browser


def ramp_answer(server_url: str, body: dict) -> dict:
    request = urllib.request.Request(f"{server_url}/api/ramp", data=json.dumps(body).encode(),
                                     headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(request) as response:
        return json.load(response)


def ramp_ready(explorer) -> dict:
    return explorer.page.evaluate("window.breakaway.rampReady()")


def body_of(state: dict) -> dict:
    body = {name: state[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "m", "k")}
    return {**body, "F_hat": state["F_hat"]}


def numbers(text: str) -> list[float]:
    return [float(n) for n in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text.replace("−", "-"))]


def set_box(explorer, label: str, value: str) -> None:
    box = explorer.page.get_by_label(label, exact=True)
    box.fill(value)
    box.dispatch_event("change")
    explorer.ready()


def test_ramp_plot_and_explanation_follow_k_and_m(explorer, server_url):
    explorer.open("?sim=0&k=0.5")
    shown = ramp_ready(explorer)
    expected = ramp_answer(server_url, body_of(explorer.state()))
    assert shown["u_ba"] == pytest.approx(expected["u_ba"], rel=1e-9)
    traces = explorer.traces("ramp")
    assert {"u = k·t (actuation)", "F (friction)", "ẋ (right axis)"} <= set(traces)
    assert traces["u = k·t (actuation)"]["x"][-1] == pytest.approx(expected["t_ba"], rel=1e-6)
    explain = explorer.page.locator("#ba-explain").inner_text()
    assert "k = 0.5 N/s" in explain
    values = numbers(explain)
    # u_ba and E13 appear with 3 significant digits: within 1 %
    assert any(v == pytest.approx(expected["u_ba"], rel=0.01) for v in values)
    assert any(v == pytest.approx(expected["E13"], rel=0.01) for v in values)
    assert "They differ because" in explain or "They agree" in explain
    assert "simulation" in explorer.traces("phase")

    set_box(explorer, "k [N/s]", "10")
    after_k = ramp_ready(explorer)
    assert after_k["t_ba"] != pytest.approx(shown["t_ba"], rel=0.01)
    assert "k = 10 N/s" in explorer.page.locator("#ba-explain").inner_text()
    t_end = explorer.traces("ramp")["u = k·t (actuation)"]["x"][-1]
    assert t_end == pytest.approx(after_k["t_ba"], rel=1e-6)

    set_box(explorer, "m [kg]", "0.001")
    after_m = ramp_ready(explorer)
    expected = ramp_answer(server_url, body_of(explorer.state()))
    assert after_m["u_ba"] == pytest.approx(expected["u_ba"], rel=1e-9)
    assert after_m["u_ba"] != pytest.approx(after_k["u_ba"], rel=1e-3)


def test_play_moves_a_cursor_and_the_glossary_explains_the_equations(explorer):
    explorer.open("?sim=0&k=2.01")
    ramp_ready(explorer)
    play = explorer.page.get_by_role("button", name="Play")
    play.click()
    assert explorer.page.locator("#ramp-play").get_attribute("aria-pressed") == "true"
    until(explorer.page, "() => document.getElementById('plot-ramp').data"
                    ".some(t => t.name === 'time cursor')")
    until(explorer.page, "() => document.getElementById('ramp-play')"
                    ".getAttribute('aria-pressed') === 'false'")
    glossary = explorer.page.locator("#glossary")
    glossary.locator("summary").click()
    text = glossary.inner_text()
    for term in ("E2", "E4", "E6′", "E12", "E13", "F̂", "z*", "BIC"):
        assert term in text, term
    assert "MODEL.md" not in explorer.page.locator("#data-panel").inner_text()
