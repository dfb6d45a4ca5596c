"""Teaching tools: pin and compare, sweeps, the guided tour, and honest units."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.browser


def names(explorer, plot: str) -> list[str]:
    return explorer.page.evaluate(
        "(id) => document.getElementById('plot-' + id).data.map(t => t.name)", plot)


def test_pinned_curves_stay_while_a_slider_moves_and_clear_in_one_click(explorer):
    explorer.open("?sim=0")
    before = explorer.traces("breakaway")["F̂ = avg"]
    explorer.page.get_by_role("button", name="Pin these curves").click()
    explorer.ready()
    box = explorer.page.get_by_label("Fs [N]", exact=True)
    box.fill("2")
    explorer.ready()
    for plot in ("stribeck", "hysteresis", "phase", "breakaway"):
        assert "pinned" in names(explorer, plot), plot
    pinned = explorer.traces("breakaway")["pinned: F̂ = avg"]
    assert pinned["y"] == before["y"]
    assert explorer.traces("breakaway")["F̂ = avg"]["y"] != before["y"]
    explorer.page.get_by_role("button", name="Clear pinned").click()
    explorer.ready()
    assert not [n for n in names(explorer, "breakaway") if n.startswith("pinned")]


def test_a_sweep_overlays_at_least_five_distinct_curves(explorer):
    explorer.open("?sim=0")
    explorer.page.get_by_label("Sweep", exact=True).select_option("V")
    explorer.page.get_by_role("button", name="Run sweep").click()
    status = explorer.page.locator("#sweep-status")
    status.get_by_text("curves of").wait_for()
    traces = explorer.traces("breakaway")
    swept = {n: t for n, t in traces.items() if n.startswith("V = ")}
    assert len(swept) >= 5
    assert len({tuple(t["y"]) for t in swept.values()}) == len(swept)
    loops = [n for n in names(explorer, "hysteresis") if n.startswith("V = ")]
    assert len(loops) == len(swept)


def test_the_tour_steps_through_the_figures_and_changes_the_plots(explorer):
    explorer.open("?sim=0")
    explorer.page.get_by_role("button", name="Start the tour").click()
    explorer.ready()
    step = explorer.page.locator("#tour-step")
    assert step.inner_text().startswith("Step 1 of")
    assert "Fig. 4" in step.inner_text()
    seen = []
    for _ in range(3):
        explorer.page.get_by_role("button", name="Next step").click()
        explorer.ready()
        seen.append((step.inner_text(), explorer.state()["k"],
                     explorer.traces("phase")[next(n for n in names(explorer, "phase")
                                                   if n.startswith("current k"))]["y"][-1]))
    assert seen[0][0].startswith("Step 2 of") and "Fig. 1" in seen[0][0]
    assert "Fig. 3" in seen[1][0] and seen[1][1] == 0.01
    assert seen[2][1] == 20 and seen[2][2] > 100 * seen[1][2]


def test_normalised_presets_say_so_and_the_lab_preset_is_si(explorer):
    explorer.open("?sim=0")
    note = explorer.page.locator("#units-note")
    assert note.is_visible() and "Normalised units" in note.inner_text()
    assert "normalised units" in explorer.page.locator("#preset-description").inner_text()
    explorer.page.get_by_label("Preset", exact=True).select_option("lab-stage")
    explorer.ready()
    assert not note.is_visible()
    assert "SI units" in explorer.page.locator("#preset-description").inner_text()
