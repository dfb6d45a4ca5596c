"""The control loop view (a PID position loop on the model's friction): its plots and sentence follow Ki, the friction
sliders and the compensation, live and settled; its numbers are those of
``breakaway.loop.loop_experiment`` run here on the same parameters; its state is in the
URL; the tour reaches it; and on a phone it is one card of the strip."""

from __future__ import annotations

from urllib.parse import parse_qs, urlparse

import numpy as np
import pytest

from breakaway.loop import loop_experiment
from breakaway.params import DEFAULTS, LOOP_COMMON, LOOP_DEFAULTS

from browser_model import until, values

pytestmark = pytest.mark.browser

LOOP = LOOP_DEFAULTS["presliding"]
PLOTS = ("loop-position", "loop-error", "loop-force")

#: Each change of #plots data-loop-frame, with whether the plots were settled then and
#: whether the loop's force plot showed a live canvas.
RECORD = """
(() => {
  window.__loopFrames = [];
  document.addEventListener('DOMContentLoaded', () => {
    const plots = document.getElementById('plots');
    new MutationObserver(() => window.__loopFrames.push({
      ready: plots.dataset.ready,
      live: document.getElementById('plot-loop-force').dataset.live,
    })).observe(plots, {attributes: true, attributeFilter: ['data-loop-frame']});
  });
})();
"""


def direct(**changes) -> dict:
    """The loop run by the library at the page's defaults with `changes` (flat names:
    friction, m, Kp, Ki, Kd, u_max, kind, h, w, f, scale)."""
    friction = {name: changes.get(name, DEFAULTS[name])
                for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "z_ba")}
    params = {**friction, "m": changes.get("m", LOOP["m"])}
    controller = {name: changes.get(name, LOOP[name]) for name in ("Kp", "Ki", "Kd", "u_max")}
    reference = {"kind": changes.get("kind", "step"),
                 **{name: changes.get(name, LOOP[name]) for name in ("h", "w", "f")}}
    steady = {name: friction[name] for name in ("Fc", "Fs", "V", "delta", "sigma")}
    return loop_experiment("presliding", params, controller, reference, LOOP_COMMON["duration"],
                           compensation={"scale": changes.get("scale", 0.0), "params": steady},
                           F_hat=DEFAULTS["F_hat"])


def js3(value: float) -> str:
    """A number as the page writes it: 3 significant digits, no trailing zeros."""
    return f"{float(f'{value:.3g}'):g}"


def loop_ready(explorer) -> dict:
    return explorer.page.evaluate("window.breakaway.loopReady()")


def sentence(explorer) -> str:
    return explorer.page.locator("#loop-explain").inner_text()


def test_the_default_loop_hunts_and_says_why(explorer):
    explorer.open("?sim=0")
    shown = loop_ready(explorer)
    run = direct()
    hunting = run["hunting"]
    assert shown["hunting"]["period"] == pytest.approx(hunting["period"], rel=1e-9)
    text = sentence(explorer)
    assert text.startswith(f"The loop hunts: {hunting['count']} break-aways in the last 2.5 s, one every "
                           f"{js3(hunting['period'])} s (a full cycle {js3(hunting['cycle'])} s), "
                           f"e within ±{js3(hunting['amplitude'])} m in the last half")
    last = run["stick_phases"][-1]
    assert (f"the last stick broke away at |u| = {js3(abs(last['u_ba']))} N with k = {js3(last['k'])} N/s, "
            f"where E13 (F̂ = avg) says {js3(abs(last['E13']))} N") in text
    # Kd against the Stribeck curve's steepest fall (Fs − Fc)/V = 0.005 N·s/m (δ = 1)
    assert "Kd + σ = 0.003 N·s/m is below the Stribeck curve's steepest fall, 0.005 N·s/m" in text
    # the variants, run: Fs = Fc settles; Kd = 0.006 ends the hunting; a step is not compensated
    settled = direct(Fs=DEFAULTS["Fc"])
    assert settled["hunting"] is None
    assert "With Fs = Fc the same loop settles" in text
    assert direct(Kd=0.006)["hunting"] is None and "with Kd = 0.006 N·s/m" in text
    assert "it adds c·Fss(ṙ), and a step's ṙ is 0 after t = 0" in text
    # the plots: x and e as the library's run (float32 on the wire), every phase marked
    position = explorer.traces("loop-position")
    np.testing.assert_allclose(values(position["x (position)"]["y"]), run["x"], rtol=1e-5, atol=1e-5)
    force = explorer.traces("loop-force")
    phases = run["stick_phases"]
    np.testing.assert_allclose(values(force["u_ba (simulated)"]["y"]), [p["u_ba"] for p in phases], rtol=1e-9)
    np.testing.assert_allclose(values(force["E13 at k (F̂ = avg)"]["y"]), [p["E13"] for p in phases], rtol=1e-9)
    assert explorer.traces("loop-error")[f"hunting: ±{js3(hunting['amplitude'])} m"]["y"][0] == pytest.approx(
        hunting["amplitude"], rel=1e-9)
    # the table: each phase's simulated break-away beside E13
    rows = explorer.page.locator("#loop-phases-table tbody tr")
    assert rows.count() == len(phases)
    cells = rows.nth(len(phases) - 1).locator("td").all_inner_texts()
    assert float(cells[3]) == pytest.approx(last["u_ba"], rel=1e-3)
    assert float(cells[4]) == pytest.approx(last["E13"], rel=1e-3)


def test_moving_ki_redraws_the_loop_live_and_its_sentence(explorer):
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0")
    page = explorer.page
    loop_ready(explorer)
    before = explorer.traces("loop-position")["x (position)"]["y"]
    # the loop's plots in view, as a person moving its gains watches them (out of view
    # their live frames wait: tests/browser/test_browser_live_frames.py)
    page.evaluate("document.getElementById('card-loop').scrollIntoView()")
    mark = page.evaluate("window.__loopFrames.length")
    slider = page.get_by_label("Ki [N/(m·s)] slider", exact=True)
    slider.focus()
    slider.press("Home")  # the left end: Ki = 0, no integral action
    # drawn at once on the loop's canvases, before the plots settle
    until(page, f"window.__loopFrames.slice({mark}).some((f) => f.ready === 'false' && f.live === 'true')")
    shown = loop_ready(explorer)
    assert explorer.state()["Ki"] == 0 and shown["controller"]["Ki"] == 0
    assert parse_qs(urlparse(page.url).query)["Ki"] == ["0"]
    run = direct(Ki=0.0)
    text = sentence(explorer)
    assert text.startswith(f"The loop does not hunt, but stops short: the body sticks with e = {js3(run['e'][-1])} m left")
    assert f"Without integral action (Ki = 0) nothing ramps u while the body sticks: Kp·|e| = {js3(0.03 * abs(run['e'][-1]))} N" in text
    after = explorer.traces("loop-position")["x (position)"]["y"]
    assert after != before
    np.testing.assert_allclose(values(after), run["x"], rtol=1e-5, atol=1e-5)
    assert "hunting" not in " ".join(explorer.traces("loop-error"))
    # Ki typed back: the loop hunts again
    box = page.get_by_label("Ki [N/(m·s)]", exact=True)
    box.fill("3")
    box.dispatch_event("change")
    loop_ready(explorer)
    assert sentence(explorer).startswith("The loop hunts")


#: One input on a slider, as a hand moving it (no release), then the loop's next frame:
#: what the page shows at that frame, read in the same task.
MOVE_AND_READ = """async ([slider, value]) => {
  const plots = document.getElementById('plots');
  const frame = plots.dataset.loopFrame;
  const range = document.getElementById(slider + '-range');
  range.value = String(value);
  range.dispatchEvent(new Event('input', {bubbles: true}));
  while (plots.dataset.loopFrame === frame) await new Promise((resolve) => requestAnimationFrame(resolve));
  const phases = document.getElementById('loop-phases');
  return {ready: plots.dataset.ready, stale: phases.dataset.stale, busy: phases.getAttribute('aria-busy'),
    rows: document.querySelectorAll('#loop-phases-table tbody tr').length,
    shown: window.breakaway.loopParams().Fs, sentence: document.getElementById('loop-explain').textContent};
}"""


def test_the_phase_table_waits_for_the_hand_to_rest_and_says_it_is_stale(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    before = loop_ready(explorer)
    page.evaluate("document.getElementById('card-loop').scrollIntoView()")
    rows = page.locator("#loop-phases-table tbody tr")
    assert rows.count() == len(before["stick_phases"]) and rows.count() > 0
    position = page.evaluate("Number(document.getElementById('Fs-range').value)")
    moving = page.evaluate(MOVE_AND_READ, ["Fs", position + 60])
    # the plots and the sentence show the new Fs at once; the table keeps the rows it had,
    # dimmed and marked busy, while the hand moves
    assert moving["ready"] == "false" and moving["shown"] == explorer.state()["Fs"] > DEFAULTS["Fs"]
    assert moving["stale"] == "true" and moving["busy"] == "true"
    assert moving["rows"] == len(before["stick_phases"])
    page.evaluate("document.getElementById('Fs-range').dispatchEvent(new Event('change', {bubbles: true}))")
    after = loop_ready(explorer)
    assert after["params"]["Fs"] == moving["shown"]
    assert page.evaluate("document.getElementById('loop-phases').dataset.stale") == "false"
    assert rows.count() == len(after["stick_phases"]) != len(before["stick_phases"])
    last = rows.nth(rows.count() - 1).locator("td").all_inner_texts()
    assert float(last[3]) == pytest.approx(after["stick_phases"][-1]["u_ba"], rel=1e-3)


def test_a_friction_slider_moves_the_loop_live_and_fs_equal_fc_settles_it(explorer):
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0")
    page = explorer.page
    loop_ready(explorer)
    # off the screen (below the ramp at 1280×800) the loop waits for the hand to rest
    mark = page.evaluate("window.__loopFrames.length")
    page.get_by_label("Fs [N] slider", exact=True).focus()
    page.keyboard.press("ArrowLeft")
    loop_ready(explorer)
    frames = page.evaluate(f"window.__loopFrames.slice({mark})")
    assert frames and all(f["ready"] == "true" for f in frames)
    # on the screen, it follows the friction live
    page.get_by_role("button", name="Show the control loop", exact=True).click()
    mark = page.evaluate("window.__loopFrames.length")
    page.get_by_label("Fs [N] slider", exact=True).focus()
    page.keyboard.press("ArrowLeft")
    until(page, f"window.__loopFrames.slice({mark}).some((f) => f.ready === 'false' && f.live === 'true')")
    explorer.ready()
    box = page.get_by_label("Fs [N]", exact=True)
    box.fill("1")
    box.dispatch_event("change")
    shown = loop_ready(explorer)
    assert shown["params"]["Fs"] == 1.0 and shown["hunting"] is None
    run = direct(Fs=1.0)
    text = sentence(explorer)
    assert text.startswith("The loop settles: no break-away in the last half")
    assert f"(|e| ≤ {js3(np.abs(run['e'][run['t'] >= 2.5]).max())} m over the last half)" in text
    assert "It settles because Fs = Fc" in text
    assert len(explorer.traces("loop-force")["u_ba (simulated)"]["x"]) == len(run["stick_phases"])


def test_compensation_on_a_sine_is_judged_from_the_numbers(explorer):
    # the README's finding: at the default Kd compensation from ṙ raises the error, with
    # more Kd it lowers it; the sentence says so from the variants it runs
    explorer.open("?sim=0&ref=sine")
    page = explorer.page
    loop_ready(explorer)
    off = direct(kind="sine")["rms_error"]
    on = direct(kind="sine", scale=1.0)["rms_error"]
    assert on > 2 * off
    more_off = direct(kind="sine", Kd=0.006)["rms_error"]
    more_on = direct(kind="sine", Kd=0.006, scale=1.0)["rms_error"]
    assert more_on < more_off
    text = sentence(explorer)
    assert (f"Exact compensation (c = 1) would raise the RMS error from {js3(off)} m to {js3(on)} m: "
            "Fss(ṙ) assumes the body follows the reference's velocity ṙ, but at Kd = 0.003 N·s/m "
            "it sticks and slips instead") in text
    assert f"At Kd = 0.006 N·s/m it lowers it instead, from {js3(more_off)} m to {js3(more_on)} m." in text
    page.get_by_label("Compensation", exact=True).select_option("exact")
    shown = loop_ready(explorer)
    assert shown["compensation"]["scale"] == 1.0
    assert shown["rms_error"] == pytest.approx(on, rel=1e-6)
    assert f"Compensation (c = 1) raises the RMS error from {js3(off)} m to {js3(on)} m" in sentence(explorer)
    box = page.get_by_label("Kd [N·s/m]", exact=True)
    box.fill("0.01")
    box.dispatch_event("change")
    loop_ready(explorer)
    helped = direct(kind="sine", Kd=0.01, scale=1.0)["rms_error"]
    unhelped = direct(kind="sine", Kd=0.01)["rms_error"]
    assert helped < unhelped / 2
    assert f"Compensation (c = 1) lowers the RMS error from {js3(unhelped)} m to {js3(helped)} m." in sentence(explorer)


def test_the_loop_state_round_trips_through_the_url(explorer):
    explorer.open("?sim=0&Ki=1.5&ref=sine&h=4&f=1&comp=scaled&c=0.75&limit=1&u_max=3&m_loop=2e-5&Kd=-1")
    page = explorer.page
    shown = loop_ready(explorer)
    assert shown["controller"] == {"Kp": LOOP["Kp"], "Ki": 1.5, "Kd": LOOP["Kd"], "u_max": 3.0}
    assert shown["reference"] == {"kind": "sine", "h": 4.0, "w": LOOP["w"], "f": 1.0}
    assert shown["compensation"]["scale"] == 0.75 and shown["params"]["m"] == 2e-5
    # a bad value keeps the default; the URL holds the valid state
    query = parse_qs(urlparse(page.url).query)
    assert query["Kd"] == [str(LOOP["Kd"])] and query["ref"] == ["sine"] and query["limit"] == ["1"]
    assert page.get_by_label("Compensation scale c", exact=True).input_value() == "0.75"
    assert page.get_by_label("Force limit u_max [N]", exact=True).is_visible()
    assert not page.get_by_label("Ramp speed w [m/s]", exact=True).is_visible()
    # a typed value the loop cannot use shows its error and is not taken
    box = page.get_by_label("Sine frequency f [Hz]", exact=True)
    box.fill("50")
    assert page.locator("#f-error").inner_text() == "f must be ≤ 40 Hz (200 periods in 5 s)"
    assert explorer.state()["f"] == 1.0
    # Reset returns the loop to its defaults too
    page.get_by_role("button", name="Reset", exact=True).click()
    shown = loop_ready(explorer)
    assert shown["controller"]["Ki"] == LOOP["Ki"] and shown["reference"]["kind"] == "step"


def test_the_tour_ends_on_the_loop_hunting_then_settling(explorer):
    explorer.open("?sim=0&Ki=1")
    page = explorer.page
    page.get_by_role("button", name="Start the tour").click()
    for _ in range(7):
        page.get_by_role("button", name="Next step").click()
    explorer.ready()
    assert "The control loop: a PID position loop" in page.locator("#tour-step").inner_text()
    assert explorer.state()["Ki"] == LOOP["Ki"]  # the step starts from the loop's defaults
    loop_ready(explorer)
    assert sentence(explorer).startswith("The loop hunts")
    page.get_by_role("button", name="Next step").click()
    explorer.ready()
    assert "Fs = Fc" in page.locator("#tour-step").inner_text()
    loop_ready(explorer)
    assert sentence(explorer).startswith("The loop settles")


def test_the_glossary_defines_hunting_windup_and_compensation(explorer):
    explorer.open("?sim=0")
    terms = explorer.page.locator("#glossary dt").all_text_contents()
    assert {"hunting", "integral windup", "compensation", "stick phase"} <= set(terms)


PHONE = {"width": 390, "height": 844}
BOX = """(selector) => { const r = document.querySelector(selector).getBoundingClientRect();
    return {top: r.top, bottom: r.bottom, left: r.left, right: r.right}; }"""


def test_on_a_phone_the_loop_is_one_card_with_its_plots_picked(explorer):
    page = explorer.page
    page.set_viewport_size(PHONE)
    explorer.open("?sim=0")
    loop_ready(explorer)
    slider = page.get_by_label("Kd [N·s/m] slider", exact=True)
    slider.focus()
    until(page, "document.getElementById('plots').dataset.inView === 'loop'")
    slider.press("PageUp")
    loop_ready(explorer)
    card = page.evaluate(BOX, "#card-loop")
    graph = page.evaluate(BOX, "#plot-loop-position")
    control = slider.bounding_box()
    assert 0 <= card["left"] and card["right"] <= PHONE["width"]
    assert 0 <= graph["top"] and graph["bottom"] <= control["y"]
    assert control["y"] + control["height"] <= PHONE["height"]
    assert page.evaluate("document.documentElement.scrollWidth") <= PHONE["width"]
    assert page.locator("#loop-explain").is_visible()
    # one of the loop's plots at a time, picked above it; the picker's six names all fit
    page.get_by_role("button", name="Force", exact=True).click()
    shown = page.evaluate("""() => ['loop-position', 'loop-error', 'loop-force'].filter(
        (id) => getComputedStyle(document.getElementById('plot-' + id)).visibility === 'visible')""")
    assert shown == ["loop-force"]
    clipped = page.evaluate("""() => [...document.querySelectorAll('.plot-picker button, .loop-picker button')]
        .filter((b) => b.scrollWidth > b.clientWidth || b.offsetWidth < 44 || b.offsetHeight < 44)
        .map((b) => b.textContent)""")
    assert clipped == []
    # the stick-phase table follows the controls and does not widen the page
    page.locator("#loop-phases").scroll_into_view_if_needed()
    assert page.evaluate("document.documentElement.scrollWidth") <= PHONE["width"]


@pytest.mark.parametrize("delta", [1.0, 1.5, 2.0, 4.0, 0.5, -1.0])
def test_the_steepest_fall_the_sentence_quotes_is_the_stribeck_curves(explorer, delta):
    from breakaway.steady import steady_state_force

    explorer.open("?sim=0")
    fall = explorer.page.evaluate("""async (delta) => (await import('/js/loop/loopexplain.js'))
        .steepestFall({Fc: 1, Fs: 1.5, V: 100, delta})""", delta)
    v = np.geomspace(1e-3, 1e4, 400_001)
    slope = -np.gradient(steady_state_force(v, 1.0, 1.5, 100.0, delta, 0.0), v)
    if delta < 0:
        assert fall == 0 and slope.max() <= 1e-8  # rises (but for the rounding)
    elif delta < 1:
        assert fall == float("inf") and slope[0] > 50 * slope[len(v) // 2]  # steeper towards v = 0
    else:
        assert fall == pytest.approx(slope.max(), rel=1e-4)


def test_axe_finds_nothing_serious_on_the_loop_on_a_phone(explorer):
    from axe_playwright_python.sync_playwright import Axe

    page = explorer.page
    page.set_viewport_size(PHONE)
    explorer.open("?sim=0&ref=sine&comp=exact")
    page.get_by_role("button", name="Control loop", exact=True).click()
    loop_ready(explorer)
    # the loop's card, its sentence, its table and its controls (the other cards' captions
    # scroll on a phone without a focusable element: axe's scrollable-region-focusable)
    context = {"include": [["#card-loop"], ["#loop-explain"], ["#loop-phases"], ["#loop-controls"]]}
    violations = [v["id"] for v in Axe().run(page, context=context).response["violations"]
                  if v["impact"] in {"serious", "critical"}]
    assert violations == []
