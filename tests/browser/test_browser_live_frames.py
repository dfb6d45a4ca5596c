"""Live frames: while a hand moves a slider (keys either way, a pointer drag) the plots
are drawn at once on a canvas in Plotly's own axes, from the curves computed in the
page; once the hand stops, the server's frame is drawn by Plotly."""

from __future__ import annotations

import json

import pytest

from breakaway.params import DEFAULTS

from browser_model import assert_plots_match_model, until

pytestmark = pytest.mark.browser

MODEL_PLOTS = ("stribeck", "hysteresis", "phase", "breakaway")

#: Each change of #plots data-frame / data-ramp-frame, with what the page had done when
#: it came: Plotly calls, live drawings, and /api/explore and /api/ramp requests sent.
RECORD = """
(() => {
  window.__sent = {explore: [], ramp: []};
  const original = window.fetch;
  window.fetch = (url, options) => {
    for (const name of ['explore', 'ramp']) {
      if (String(url).endsWith('/api/' + name)) window.__sent[name].push(JSON.parse(options.body));
    }
    return original(url, options);
  };
  window.__frames = [];
  // when each input arrives [ms]: a hand rests where the gap reaches the settle window
  window.__inputs = [];
  document.addEventListener('input', () => window.__inputs.push(performance.now()), true);
  document.addEventListener('DOMContentLoaded', () => {
    const plots = document.getElementById('plots');
    const last = {};
    new MutationObserver((records) => {
      for (const record of records) {
        const value = plots.getAttribute(record.attributeName);
        if (last[record.attributeName] === value) continue; // written again, unchanged
        last[record.attributeName] = value;
        window.__frames.push({what: record.attributeName, value,
          ready: plots.dataset.ready, surfaces: window.breakaway.surfaces(),
          explore: window.__sent.explore.length, ramp: window.__sent.ramp.length});
      }
    }).observe(plots, {attributes: true, attributeFilter: ['data-frame', 'data-ramp-frame']});
  });
})();
"""


def recorded(page) -> list[dict]:
    return page.evaluate("window.__frames")


def sent(page, name: str) -> list[dict]:
    return page.evaluate(f"window.__sent.{name}")


def frame_changes(page, since: int) -> list[dict]:
    """The data-frame changes after the first `since` records."""
    return [r for r in recorded(page)[since:] if r["what"] == "data-frame"]


def assert_settled_without_canvas(page) -> None:
    """After the settle every plot shows Plotly's drawing, no live canvas."""
    for plot in MODEL_PLOTS:
        assert page.evaluate(
            """(id) => { const gd = document.getElementById('plot-' + id);
                const canvas = gd.querySelector('canvas.live-layer');
                return gd.dataset.live !== 'true' && (!canvas || canvas.style.display === 'none')
                    && getComputedStyle(gd.querySelector('.cartesianlayer')).visibility === 'visible'; }""",
            plot), plot


def test_arrow_steps_either_way_are_drawn_live_at_once_then_settle(explorer):
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0&Fc=1.5&Fs=1.5")
    page = explorer.page
    slider = page.get_by_label("Fc [N] slider", exact=True)
    slider.focus()
    history = page.evaluate("history.length")
    for key in ("ArrowRight", "ArrowLeft", "ArrowLeft", "ArrowRight"):
        mark = len(recorded(page))
        before = page.evaluate("window.breakaway.surfaces()")
        requests = len(sent(page, "explore"))
        slider.press(key)
        until(page, f"window.__frames.length > {mark}")
        first = frame_changes(page, mark)[0]
        # shown live: the four plots on their canvases, with no request and no Plotly call
        # (the control loop's three too, when its answer came first: it follows Fc live)
        assert first["ready"] == "false"
        assert first["surfaces"]["live"] - before["live"] in (4, 7)
        assert first["surfaces"]["reacts"] == before["reacts"]
        assert first["explore"] == requests
        explorer.ready()
        # then settled: one request for the state the hand stopped on, Plotly's plots
        assert len(sent(page, "explore")) == requests + 1
        assert len(frame_changes(page, mark)) == 1  # the settle shows no new state
        state = explorer.state()
        assert state["Fs"] >= state["Fc"]  # Fs follows Fc up (MODEL.md §1)
        assert_plots_match_model(explorer, state)
        assert_settled_without_canvas(page)
    assert page.evaluate("history.length") == history + 4  # each step a history entry


def test_a_held_arrow_key_asks_once_and_ends_on_the_models_plots(explorer):
    # key repeat, 30 ms apart: every press is drawn live, the server asked once at the end
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("δ (delta) slider", exact=True)
    slider.focus()
    mark = len(recorded(page))
    for i in range(24):
        page.keyboard.press("ArrowRight" if i < 16 else "ArrowLeft")
        page.wait_for_timeout(30)
    explorer.ready()
    state = explorer.state()
    assert state["delta"] != DEFAULTS["delta"]
    assert float(page.get_by_label("δ (delta)", exact=True).input_value()) == state["delta"]
    assert_plots_match_model(explorer, state)
    assert len(frame_changes(page, mark)) >= 12  # at most two presses in one animation frame
    assert len(sent(page, "explore")) <= 1 + 3  # the first frame, then only where the hand rested


def test_a_pointer_drag_is_drawn_live_and_asks_the_server_once_released(explorer):
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("k [N/s] slider", exact=True)
    slider.scroll_into_view_if_needed()
    box = slider.bounding_box()
    y = box["y"] + box["height"] / 2
    start = page.evaluate("(() => { const r = document.getElementById('k-range');"
                          " return (r.value - r.min) / (r.max - r.min); })()")
    x = box["x"] + 8 + start * (box["width"] - 16)  # the thumb's centre
    mark = len(recorded(page))
    requests = len(sent(page, "explore"))
    inputs = page.evaluate("window.__inputs.length")
    page.mouse.move(x, y)
    page.mouse.down()
    for step in range(1, 31):
        page.mouse.move(x + step * 4, y)
        page.wait_for_timeout(16)
    during = frame_changes(page, mark)
    assert len(during) >= 10
    # the hand rests only where its inputs stop for a settle window: none while it moves
    # every 16 ms, unless the machine running the test stalls that long (a loaded
    # runner), and then the settled drawing may come in at each such rest
    times = page.evaluate(f"window.__inputs.slice({inputs})")
    settle = page.evaluate("window.breakaway.settleMs")
    rests = sum(later - earlier >= settle for earlier, later in zip(times, times[1:]))
    assert len(times) >= 10
    assert all(r["explore"] <= requests + rests for r in during)
    if rests == 0:
        assert all(r["ready"] == "false" for r in during)
    page.mouse.up()
    explorer.ready()
    asked = sent(page, "explore")[requests:]
    assert 1 <= len(asked) <= 1 + rests
    assert asked[-1]["k"] == explorer.state()["k"] > DEFAULTS["k"]
    assert_plots_match_model(explorer)
    assert_settled_without_canvas(page)


def test_the_live_frame_keeps_a_zoom_and_a_hidden_trace(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    page.evaluate("Plotly.relayout('plot-stribeck', {'xaxis.range': [-0.5, 0.5]})")
    page.locator("#plot-hysteresis .legendtoggle").first.click()
    until(page, "document.getElementById('plot-hysteresis').data[0].visible === 'legendonly'")
    slider = page.get_by_label("Fs [N] slider", exact=True)
    slider.focus()
    frames = explorer.frames()
    slider.press("ArrowRight")
    until(page, f"window.breakaway.frames() > {frames}")
    ranges = json.loads(page.locator("#plot-stribeck canvas.live-layer").get_attribute("data-ranges"))
    assert ranges["x"] == [-0.5, 0.5]
    explorer.ready()
    assert page.evaluate("document.getElementById('plot-stribeck').layout.xaxis.range") == [-0.5, 0.5]
    assert page.evaluate("document.getElementById('plot-hysteresis').data[0].visible") == "legendonly"
    assert_plots_match_model(explorer, explorer.state())


#: Plotly's own range and tick labels of each axis of each plot, and the live drawing's
#: for the same figure.
AXES = """async () => {
  const { liveAxes } = await import('/js/plots/liveaxes.js');
  const out = [];
  for (const gd of document.querySelectorAll('#plots .js-plotly-plot')) {
    const mine = liveAxes(gd, {data: gd.data, layout: gd.layout});
    for (const [key, axis] of Object.entries(gd._fullLayout)) {
      if (!/^[xy]axis\\d*$/.test(key)) continue;
      const id = key[0] + key.slice(5);
      const [lo, hi] = [Math.min(...mine[id].range), Math.max(...mine[id].range)];
      out.push({plot: gd.id, axis: id, plotly: axis.range, live: mine[id].range,
        plotlyTicks: axis._vals.map((v) => v.text),
        liveTicks: mine[id].ticks.filter(([v]) => v >= lo - 1e-9 && v <= hi + 1e-9).map(([, t]) => t)});
    }
  }
  return out;
}"""


@pytest.mark.parametrize("viewport,query", [
    ((1280, 800), "?sim=1"),
    ((1920, 1080), "?sim=1&present=1&F_hat=self&k=17"),
    ((390, 844), "?sim=0&Fc=12&Fs=15&V=0.002&delta=0.7&s=200000&sigma=40&k=3&F_hat=Fc"),
    ((1280, 800), "?sim=0&V=30000&k=25&delta=-1&F_hat=self&Fs=300&Fc=2"),
])
def test_the_live_frame_has_plotlys_ranges_and_ticks(explorer, viewport, query):
    explorer.page.set_viewport_size({"width": viewport[0], "height": viewport[1]})
    explorer.open(query)
    explorer.sim_ready()
    explorer.page.evaluate("window.breakaway.rampReady()")
    axes = explorer.page.evaluate(AXES)
    assert len(axes) == 17  # two axes on each plot, three on the ramp's
    for axis in axes:
        span = abs(axis["plotly"][1] - axis["plotly"][0])
        assert all(abs(a - b) <= 1e-9 * span for a, b in zip(axis["live"], axis["plotly"])), axis
        assert axis["liveTicks"] == axis["plotlyTicks"], axis


def test_a_step_of_the_mass_draws_the_ramp_live_from_the_pages_own_run(explorer):
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0")
    page = explorer.page
    slider = page.get_by_label("m [kg] slider", exact=True)
    slider.focus()
    for _ in range(2):
        mark = len(recorded(page))
        slider.press("ArrowRight")
        until(page, f"window.__frames.slice({mark}).some((r) => r.what === 'data-ramp-frame')")
        ramp = next(r for r in recorded(page)[mark:] if r["what"] == "data-ramp-frame")
        # drawn live, before the settle, from the run the page made (rampmodel.js)
        assert ramp["ready"] == "false"
        assert page.evaluate("window.breakaway.viewParams('ramp').m") == explorer.state()["m"]
    page.evaluate("window.breakaway.rampReady()")
    assert explorer.state()["m"] > DEFAULTS["m"]
    # the default run is short: the server is not asked, ahead or at all
    assert sent(page, "ramp") == []
    page.evaluate("window.breakaway.rampReady()")
    assert sent(page, "explore") == [sent(page, "explore")[0]]  # m asks for no frame


#: A live frame for plot `id` with its curves' y doubled, from the surfaces module itself:
#: the draws counted before and after, and whether the graph then shows the canvas.
LIVE_DOUBLED = """async (id) => {
  const { live, surfaceStats } = await import('/js/plots/surfaces.js');
  const gd = document.getElementById('plot-' + id);
  const before = surfaceStats.live;
  const figure = {data: gd.data.map((trace) => ({...trace, y: Array.from(trace.y ?? [], (v) => 2 * v)})),
    layout: gd.layout};
  const shown = live(id, figure);
  return {shown, before, after: surfaceStats.live, live: gd.dataset.live === 'true'};
}"""


def test_a_live_frame_of_a_plot_out_of_view_is_drawn_once_it_comes_into_view(explorer):
    # while the hand moves the loop's friction, the model's plots above the loop's card
    # are out of view: their frames wait, and the one they missed is drawn on scrolling back
    explorer.open("?sim=0")
    page = explorer.page
    page.evaluate("document.getElementById('card-loop').scrollIntoView()")
    until(page, "document.getElementById('plot-stribeck').getBoundingClientRect().bottom < 0")
    page.wait_for_timeout(100)  # the intersection observer's first report
    out_of_view = page.evaluate(LIVE_DOUBLED, "stribeck")
    assert out_of_view["shown"] is True  # taken: the caller counts its frame
    assert out_of_view["after"] == out_of_view["before"] and not out_of_view["live"]
    page.evaluate("document.getElementById('plot-stribeck').scrollIntoView()")
    until(page, "document.getElementById('plot-stribeck').dataset.live === 'true'")
    assert page.evaluate("window.breakaway.surfaces().live") == out_of_view["before"] + 1
    # what it drew is the frame it missed: the doubled curves' range
    ranges = json.loads(page.locator("#plot-stribeck canvas.live-layer").get_attribute("data-ranges"))
    plotly = page.evaluate("document.getElementById('plot-stribeck')._fullLayout.yaxis.range")
    assert ranges["y"][1] == pytest.approx(2 * plotly[1], rel=0.05)
    # in view, a frame is drawn at once
    in_view = page.evaluate(LIVE_DOUBLED, "hysteresis")
    assert in_view["shown"] and in_view["live"] and in_view["after"] == in_view["before"] + 1


#: At the next change of #plots data-frame (the press's frame, in the same task: before a
#: view's answer can redraw a plot), each model plot's live canvas compared with the same
#: plot painted anew on a canvas of its own from the figures of the page's state built
#: from scratch: the model's curves computed again, the views' figures, styled as the
#: page is shown; and the ranges drawn. Kept in window.__painted. (Compared with a canvas
#: of the same kind: the live canvas, drawn on frame after frame, may rasterise a dotted
#: line a shade apart, 4/255 at its edge pixels.)
WATCH_PAINTED_FROM_STATE = """async () => {
  const { modelFrame } = await import('/js/models/model.js');
  const { exploreBody } = await import('/js/page/state.js');
  const { pageFigures } = await import('/js/page/views.js');
  const { pageStyle } = await import('/js/plots/draw.js');
  const { styled } = await import('/js/plots/plots.js');
  const { paintAhead } = await import('/js/plots/livedraw.js');
  window.__painted = null;
  const plots = document.getElementById('plots');
  const frame = plots.dataset.frame;
  const observer = new MutationObserver(() => {
    if (plots.dataset.frame === frame) return;
    observer.disconnect();
    const state = window.breakaway.state();
    const figures = pageFigures(modelFrame(exploreBody(state)), state);
    const out = {};
    for (const id of ['stribeck', 'hysteresis', 'phase', 'breakaway']) {
      const gd = document.getElementById('plot-' + id);
      const canvas = gd.querySelector('canvas.live-layer');
      const anew = paintAhead(gd, styled(figures[id], pageStyle())).canvas;
      out[id] = {same: anew.toDataURL() === canvas.toDataURL(), ranges: canvas.dataset.ranges};
    }
    window.__painted = {checks: out, surfaces: window.breakaway.surfaces()};
  });
  observer.observe(plots, {attributes: true, attributeFilter: ['data-frame']});
}"""


def press_when_painted_ahead(explorer, label: str, key: str, painted: int) -> tuple[dict, dict]:
    """Focus slider `label`, wait until the frames one press away are painted ahead
    (`painted` of them), press `key`: the surfaces' counts before the press, and at the
    press's frame the checks of WATCH_PAINTED_FROM_STATE with the counts then."""
    page = explorer.page
    slider = page.get_by_label(label, exact=True)
    slider.focus()
    until(page, f"window.breakaway.surfaces().painted >= {painted}")
    before = page.evaluate("window.breakaway.surfaces()")
    page.evaluate(WATCH_PAINTED_FROM_STATE)
    slider.press(key)
    until(page, "window.__painted !== null")
    return before, page.evaluate("window.__painted")


@pytest.mark.parametrize("label,key,painted", [
    ("Fs [N] slider", "ArrowRight", 8),
    # k moves neither the Stribeck curve nor the loop: one frame each serves either side
    ("k [N/s] slider", "ArrowLeft", 6),
])
def test_a_key_press_copies_the_frame_painted_ahead_which_is_the_states_own(explorer, label, key, painted):
    # while the page is idle the frames one press away are painted; the press copies
    # them, and what it shows is the drawing of its own state's figures, pixel for pixel
    explorer.open("?sim=0")
    page = explorer.page
    before, shown = press_when_painted_ahead(explorer, label, key, painted)
    assert shown["surfaces"]["ahead"] - before["ahead"] == 4  # all four copied, none drawn
    for plot, check in shown["checks"].items():
        assert check["same"], plot
    explorer.ready()
    assert_plots_match_model(explorer, explorer.state())
    assert_settled_without_canvas(page)


def test_a_frame_painted_ahead_is_not_copied_once_the_graph_has_changed(explorer):
    # a zoom after the frames were painted ahead: the press draws that plot anew, in the
    # zoom, and copies the three others
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_label("Fs [N] slider", exact=True).focus()
    until(page, "window.breakaway.surfaces().painted >= 8")
    page.evaluate("Plotly.relayout('plot-stribeck', {'xaxis.range': [-0.5, 0.5]})")
    before, shown = press_when_painted_ahead(explorer, "Fs [N] slider", "ArrowRight", 8)
    assert shown["surfaces"]["ahead"] - before["ahead"] == 3
    assert json.loads(shown["checks"]["stribeck"]["ranges"])["x"] == [-0.5, 0.5]
    for plot, check in shown["checks"].items():  # the three copied, the Stribeck plot drawn (no dots)
        assert check["same"], plot
    explorer.ready()
    assert_plots_match_model(explorer, explorer.state())


def test_inputs_of_the_mass_within_one_animation_frame_run_and_draw_the_ramp_once(explorer):
    # a drag under a slow processor gives two or three inputs a frame: the ramp is run
    # and drawn once, at the animation frame, for the last of them; Play's button is
    # not written again by each answer
    explorer.page.add_init_script(RECORD)
    explorer.open("?sim=0")
    page = explorer.page
    page.evaluate("window.breakaway.rampReady()")
    out = page.evaluate("""async () => {
        const range = document.getElementById('m-range');
        const plots = document.getElementById('plots');
        const play = document.getElementById('ramp-play');
        let playWrites = 0;
        new MutationObserver((records) => { playWrites += records.length; })
          .observe(play, {attributes: true, childList: true, characterData: true, subtree: true});
        const before = Number(plots.dataset.rampFrame ?? 0);
        await new Promise((resolve) => requestAnimationFrame(resolve));
        const start = Number(range.value);
        for (const step of [1, 2, 3]) {
          range.value = String(start + step);
          range.dispatchEvent(new Event('input', {bubbles: true}));
        }
        const wanted = window.breakaway.state().m;
        await new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve)));
        const drawn = Number(plots.dataset.rampFrame) - before;
        const shown = window.breakaway.viewParams('ramp').m;
        range.dispatchEvent(new Event('change', {bubbles: true}));
        await window.breakaway.rampReady();
        return {drawn, shown, wanted, playWrites};
    }""")
    assert out["drawn"] == 1
    assert out["shown"] == out["wanted"]
    assert out["playWrites"] == 0


def test_curves_that_stay_give_the_same_arrays_and_the_legend_follows_k(explorer):
    # a drag of k: the figures of the curves that stay (the loop, the phase family) are
    # the same arrays frame after frame, not made again; the legends name each frame's k
    explorer.open("?sim=0")
    page = explorer.page
    same = page.evaluate("""async () => {
        const { modelFrame } = await import('/js/models/model.js');
        const { hysteresisFigure, phaseFigure } = await import('/js/plots/plots.js');
        const { exploreBody } = await import('/js/page/state.js');
        const state = window.breakaway.state();
        const body = exploreBody(state);
        const one = modelFrame(body);
        const two = modelFrame({...body, k: body.k * 2});
        const [h1, h2] = [hysteresisFigure(one, state), hysteresisFigure(two, state)];
        const [p1, p2] = [phaseFigure(one, state), phaseFigure(two, {...state, k: body.k * 2})];
        return {
          loop: h1.data.every((trace, i) => trace.x === h2.data[i].x && trace.y === h2.data[i].y),
          family: p1.data[0].x === p2.data[0].x && p1.data[0].y === p2.data[0].y,
          current: p1.data[1].y !== p2.data[1].y,
        }; }""")
    assert same["loop"] and same["family"] and same["current"]
    names = page.evaluate("""async () => {
        const range = document.getElementById('k-range');
        const names = [];
        for (const step of [3, 6, 9]) {
          range.value = String(Number(range.value) + step);
          range.dispatchEvent(new Event('input', {bubbles: true}));
          await new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve)));
          names.push([...document.querySelectorAll('#plot-phase .legendtext, #plot-breakaway .legendtext')]
            .map((text) => text.textContent).filter((text) => text.startsWith('current k')));
        }
        range.dispatchEvent(new Event('change', {bubbles: true}));
        return names; }""")
    explorer.ready()
    settled = page.evaluate("""[...document.querySelectorAll('#plot-phase .legendtext, #plot-breakaway .legendtext')]
        .map((text) => text.textContent).filter((text) => text.startsWith('current k'))""")
    assert len({tuple(frame) for frame in names}) == 3  # each frame its own k
    assert all(len(frame) == 2 for frame in names)
    assert names[-1] == settled  # the last live frame's names are Plotly's
