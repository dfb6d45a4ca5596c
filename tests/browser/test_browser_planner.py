"""What to measure next, in the page: the break-away plot's band of rates where F_ba(k)
is most sensitive to V and δ (held to the planner's own), and "Plan the next
experiment" under a report that leaves parameters open."""

from __future__ import annotations

import csv
import io

import numpy as np
import pytest

from breakaway.identify.synthetic import make_dataset, to_csv
from breakaway.plan.checks import _ramps_record
from breakaway.plan.sensitivity import rate_band

pytestmark = pytest.mark.browser

PANEL = "#data-panel"
BAND = "most sensitive to V, δ"


def js_band(explorer, p: dict, F_hat: str):
    return explorer.page.evaluate("""async ([p, fHat]) => {
        const { rateBand } = await import('/js/models/sensitivity.js');
        return rateBand(p, fHat); }""", [p, F_hat])


@pytest.mark.parametrize("p, F_hat", [
    (dict(Fc=1.0, Fs=1.5, V=100.0, delta=1.0, sigma=0.0, s=1.0, z_ba=0.95), "avg"),
    (dict(Fc=1.0, Fs=1.5, V=5.0, delta=2.0, sigma=0.001, s=1.0, z_ba=0.9), "self"),
    (dict(Fc=2.0, Fs=3.0, V=2e-3, delta=1.0, sigma=20.0, s=5e4, z_ba=0.95), "Fs"),
])
def test_the_page_finds_the_planners_band(explorer, p, F_hat):
    explorer.open("?sim=0")
    band = js_band(explorer, p, F_hat)
    expected = rate_band(**p, F_hat=F_hat)
    # both search the same grid of 1201 rates over 12 decades: an edge may differ by a
    # step of the grid (2.3 %) where the page's central differences (F̂ = self, whose ẋ*
    # moves with V and δ) meet the analytic derivatives at the half-way level
    np.testing.assert_allclose(band["k"], expected["k"], rtol=0.024)
    np.testing.assert_allclose(band["speed"], expected["speed"], rtol=0.024)
    assert js_band(explorer, {**p, "Fs": p["Fc"]}, F_hat) is None


def test_the_band_is_kept_by_the_parameters_it_depends_on(explorer):
    # the page makes a band once per key (bandKey): the rate k and the mass m, which a
    # drag moves, leave the band as it is; each parameter of the curve moves it
    explorer.open("?sim=0")
    p = dict(Fc=1.0, Fs=1.5, V=5.0, delta=2.0, sigma=0.001, s=1.0, z_ba=0.9, k=2.0, m=1e-4, F_hat="self")
    same, keys = explorer.page.evaluate("""async (p) => {
        const { bandKey, rateBand } = await import('/js/models/sensitivity.js');
        const moved = {...p, k: 17.5, m: 3e-3};
        const changed = {Fc: 1.1, Fs: 1.6, V: 6, delta: 1.5, sigma: 0.01, s: 2, z_ba: 0.8, F_hat: 'avg'};
        return [
          bandKey(moved) === bandKey(p)
            && JSON.stringify(rateBand(moved)) === JSON.stringify(rateBand(p)),
          Object.entries(changed).map(([name, value]) => bandKey({...p, [name]: value}) !== bandKey(p)),
        ]; }""", p)
    assert same
    assert all(keys)


def test_the_band_is_shaded_and_said_and_moves_with_V(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    shade = explorer.traces("breakaway")[BAND]
    expected = rate_band(1.0, 1.5, 100.0, 1.0)
    assert min(shade["x"]) == pytest.approx(expected["k"][0], rel=0.03)
    assert max(shade["x"]) == pytest.approx(expected["k"][1], rel=0.03)
    said = page.locator("#ba-band").inner_text()
    assert said.startswith("Shaded: the rates k = 0.45")
    assert "slower ramps break away at about Fs, faster ones at about Fc" in said
    before = page.evaluate("document.getElementById('plots').dataset.frame")
    page.get_by_label("V [m/s]", exact=True).fill("20")
    page.get_by_label("V [m/s]", exact=True).press("Enter")
    page.wait_for_function(f"() => document.getElementById('plots').dataset.frame !== '{before}'")
    explorer.ready()
    moved = explorer.traces("breakaway")[BAND]
    # the band sits where ẋ* meets V: a fifth of the rates for a fifth of V
    assert max(moved["x"]) == pytest.approx(expected["k"][1] / 5, rel=0.03)
    assert "around V = 20 m/s" in page.locator("#ba-band").inner_text()


def upload(explorer, text: str, name: str) -> None:
    explorer.page.get_by_label("Data file", exact=True).set_input_files(
        {"name": name, "mimeType": "text/csv", "buffer": text.encode()})
    explorer.page.wait_for_selector(f'{PANEL}[data-state="done"]', timeout=60_000)


def test_a_report_with_open_parameters_gets_a_plan_and_its_programme(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    upload(explorer, to_csv(_ramps_record(1, 40.0, 300.0, 0.005)), "high-rates.csv")
    box = page.get_by_role("region", name="Plan the next experiment")
    assert box.is_visible()
    assert "do not determine Fs, V, δ" in page.locator("#plan-intro").inner_text()
    # the limits start at what the record reached
    assert float(page.get_by_label("Largest force u_max [N]").input_value()) == pytest.approx(
        1.006, abs=0.001)
    assert page.get_by_label("Kind of runs").input_value() == "ramps"
    assert not page.get_by_label("Slowest speed held v_min [m/s]").is_visible()
    page.get_by_label("Largest force u_max [N]").fill("3")
    page.get_by_label("Runs", exact=True).fill("10")
    page.get_by_role("button", name="Plan", exact=True).click()
    page.locator("#plan-results").wait_for(state="visible")
    assert page.locator("#plan-design").inner_text().startswith("10 force ramps from rest, at k = ")
    notes = page.locator("#plan-notes li").all_inner_texts()
    assert any(note.startswith("V is not determined: the data show one level") for note in notes)
    plotted = page.evaluate("""() => Object.fromEntries(document.getElementById('plan-plot').data
        .map((t) => [t.name, Array.from(t.y)]))""")
    after = plotted["after the plan"]
    # Fc, Fs, V, δ: every one below the bar of 100 % after the plan
    assert len(after) == 4 and max(after) < 100
    assert len(plotted["now: no standard error"]) == 3
    with page.expect_download() as info:
        page.get_by_role("button", name="Download programme (CSV)").click()
    text = open(info.value.path(), encoding="utf-8").read()
    rows = list(csv.reader(io.StringIO("\n".join(
        line for line in text.splitlines() if not line.startswith("#")))))
    assert rows[0] == ["run", "t", "u"]
    table = np.array(rows[1:], dtype=float)
    assert set(table[:, 0].astype(int)) == set(range(1, 11)) and table[:, 2].max() <= 3.0


def test_a_bad_limit_is_named_and_the_family_changes_the_fields(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    upload(explorer, to_csv(_ramps_record(1, 40.0, 300.0, 0.005)), "high-rates.csv")
    page.get_by_label("Kind of runs").select_option("steady")
    assert page.get_by_label("Slowest speed held v_min [m/s]").is_visible()
    assert not page.get_by_label("Runs", exact=True).is_hidden()
    page.get_by_label("Kind of runs").select_option("sine")
    assert page.get_by_label("Travel [m]").is_visible() and page.get_by_label("Runs", exact=True).is_hidden()
    page.get_by_label("Largest speed v_max [m/s]").fill("fast")
    page.get_by_role("button", name="Plan", exact=True).click()
    assert "a number > 0 for “Largest speed v_max [m/s]”" in page.locator("#plan-error").inner_text()


def test_a_report_that_determines_everything_offers_no_plan(explorer):
    explorer.open("?sim=0")
    data, _ = make_dataset("steady", seed=1)
    upload(explorer, to_csv(data), "steady.csv")
    assert explorer.page.locator("#plan-box").is_hidden()
