"""Teaching tools: pin and compare, sweeps, the guided tour, and honest units."""

from __future__ import annotations

import pytest

from breakaway.settings import get_settings

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


def swept(explorer, plot: str, label: str) -> dict:
    return {n: t for n, t in explorer.traces(plot).items() if n.startswith(f"{label} = ")}


def differs_from(curve: dict, other: dict) -> bool:
    """Whether two plotted curves differ in x or in y beyond float32 round-off."""
    import numpy as np
    for axis in ("x", "y"):
        a = np.array(curve[axis], dtype=float)
        b = np.array(other[axis], dtype=float)
        if a.shape != b.shape or not np.allclose(a, b, rtol=1e-6, atol=1e-9, equal_nan=True):
            return True
    return False


def test_a_sweep_overlays_five_curves_that_all_differ_from_the_current_one(explorer):
    explorer.open("?sim=0")
    explorer.page.get_by_label("Sweep", exact=True).select_option("V")
    explorer.page.get_by_role("button", name="Run sweep").click()
    status = explorer.page.locator("#sweep-status")
    status.get_by_text("curves of").wait_for()
    state = explorer.state()
    # V moves the Stribeck curve and the break-away curve, not the loop nor the phase family
    for plot, current in (("stribeck", "Fss(v)"), ("breakaway", f"F̂ = {state['F_hat']}")):
        curves = swept(explorer, plot, "V")
        assert len(curves) == 5, plot
        assert all(float(name.split(" = ")[1]) != state["V"] for name in curves)
        now = explorer.traces(plot)[current]
        assert all(differs_from(curve, now) for curve in curves.values()), plot
        assert len({(tuple(c["x"]), tuple(c["y"])) for c in curves.values()}) == 5
    assert swept(explorer, "hysteresis", "V") == {} and swept(explorer, "phase", "V") == {}
    assert "leaves the hysteresis loop" in status.inner_text()
    # s moves the loop: five loops, none the current one
    explorer.page.get_by_label("Sweep", exact=True).select_option("s")
    explorer.page.get_by_role("button", name="Run sweep").click()
    status.get_by_text("curves of s").wait_for()
    loops = swept(explorer, "hysteresis", "s")
    assert len(loops) == 5 and all(float(n.split(" = ")[1]) != 1 for n in loops)
    current = explorer.traces("hysteresis")["moving +x"]
    assert all(differs_from(loop, current) for loop in loops.values())


def test_the_tour_steps_through_the_figures_and_changes_the_plots(explorer):
    # the page opens on the tour's first preset: the first step must still change the plots
    explorer.open("?sim=0")
    before = {plot: explorer.traces(plot) for plot in ("stribeck", "hysteresis", "phase", "breakaway")}
    explorer.page.get_by_role("button", name="Start the tour").click()
    explorer.ready()
    step = explorer.page.locator("#tour-step")
    assert step.inner_text().startswith("Step 1 of")
    assert "Fig. 4" in step.inner_text()
    explorer.page.locator("#sweep-status").get_by_text("curves of V").wait_for()
    after = explorer.traces("stribeck")
    assert len(after) == len(before["stribeck"]) + 5
    assert all(differs_from(curve, after["Fss(v)"]) for curve in swept(explorer, "stribeck", "V").values())
    seen = []
    for _ in range(3):
        explorer.page.get_by_role("button", name="Next step").click()
        explorer.ready()
        if not seen:
            # step 2 is about the loop: its sweep is of s
            explorer.page.locator("#sweep-status").get_by_text("curves of s").wait_for()
            assert len(swept(explorer, "hysteresis", "s")) == 5
        seen.append((step.inner_text(), explorer.state()["k"],
                     explorer.traces("phase")[next(n for n in names(explorer, "phase")
                                                   if n.startswith("current k"))]["y"][-1]))
    assert seen[0][0].startswith("Step 2 of") and "Fig. 1" in seen[0][0]
    assert "Fig. 3" in seen[1][0] and seen[1][1] == 0.01
    assert seen[2][1] == 20 and seen[2][2] > 100 * seen[1][2]
    assert explorer.page.locator("#sweep-status").inner_text() == ""  # Fig. 3 sweeps nothing


def test_normalised_presets_say_so_and_the_lab_preset_is_si(explorer):
    explorer.open("?sim=0")
    note = explorer.page.locator("#units-note")
    assert note.is_visible() and "Normalised units" in note.inner_text()
    assert "normalised units" in explorer.page.locator("#preset-description").inner_text()
    explorer.page.get_by_label("Preset", exact=True).select_option("lab-stage")
    explorer.ready()
    assert not note.is_visible()
    assert "SI units" in explorer.page.locator("#preset-description").inner_text()


def test_a_cold_open_explains_break_away_cites_the_note_and_remembers_its_dismissal(explorer):
    page = explorer.page
    explorer.open("?sim=0")
    page.evaluate("window.localStorage.clear()")
    explorer.open("?sim=0")
    intro = page.locator("#intro")
    assert intro.is_visible()
    text = intro.inner_text()
    # what break-away is, what the note claims (author and title), what to try first
    assert "break-away force" in text and "presliding" in text
    assert "Ruderman" in text
    assert "On break-away forces in actuated motion systems with nonlinear friction" in text
    assert "Try first" in text and "tour" in text
    # it comes first, above the controls it explains
    top = page.evaluate("document.getElementById('intro').getBoundingClientRect().top")
    assert top < page.evaluate("document.getElementById('preset').getBoundingClientRect().top")
    page.get_by_role("button", name="Hide this introduction").click()
    assert intro.is_hidden()
    assert page.evaluate("document.activeElement.id") == "preset"
    explorer.open("?sim=0")
    assert intro.is_hidden()  # remembered
    page.get_by_role("button", name="What is this?").click()
    assert intro.is_visible()
    explorer.open("?sim=0")
    assert intro.is_visible()
    # starting the tour from it puts it away and starts the tour
    page.get_by_role("button", name="Take the guided tour").click()
    explorer.ready()
    assert intro.is_hidden() and page.locator("#tour-step").inner_text().startswith("Step 1 of")
    page.evaluate("window.localStorage.clear()")


def test_the_tour_brings_every_steps_card_into_view(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    page.emulate_media(reduced_motion="reduce")
    page.get_by_role("button", name="Start the tour").click()
    cards = []
    while True:
        explorer.ready()
        step = page.locator("#tour-step").inner_text()
        plot = page.evaluate("""() => {
          const cards = [...document.querySelectorAll('.plot-card')].filter((card) => {
            const box = card.getBoundingClientRect();
            return box.top >= -1 && box.top < window.innerHeight - 100;
          });
          return cards.map((card) => card.id);
        }""")
        cards.append((step, plot))
        if page.get_by_role("button", name="Next step").is_disabled():
            break
        page.get_by_role("button", name="Next step").click()
    expected = ["card-stribeck", "card-hysteresis", "card-phase", "card-phase", "card-breakaway",
                "card-ramp", "card-breakaway", "card-loop", "card-loop"]
    assert len(cards) == len(expected)
    for (step, shown), card in zip(cards, expected):
        assert card in shown, (step, shown)


def test_views_are_named_as_a_student_would(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    assert page.locator('[role="tab"]').count() == 0  # one page: no lone tab
    links = page.get_by_role("navigation", name="On this page").get_by_role("link").all_inner_texts()
    assert links == ["The model", "Control loop", "Your data", "Glossary"]
    explorer.page.set_viewport_size({"width": 390, "height": 844})
    picker = page.get_by_role("group", name="Plot in view", exact=True).get_by_role("button").all_inner_texts()
    assert picker == ["Stribeck", "Hysteresis", "Phase", "Break-away", "Ramp", "Control loop"]


def test_nothing_the_page_shows_names_a_file_a_student_does_not_have(explorer):
    frontend = get_settings().frontend_dir
    for path in [*frontend.rglob("*.js"), *frontend.rglob("*.html"), *frontend.rglob("*.css")]:
        if "vendor" in path.parts:
            continue
        text = path.read_text(encoding="utf-8")
        assert "MODEL.md" not in text and "../shared" not in text, path
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_role("button", name="Start the tour").click()
    while not page.get_by_role("button", name="Next step").is_disabled():
        assert "§" not in page.locator("#tour-step").inner_text()
        page.get_by_role("button", name="Next step").click()
    shown = page.evaluate("document.body.innerText")
    assert ".md" not in shown and "§" not in shown
