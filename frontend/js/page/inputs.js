// From the controls to the state: each slider, number box, menu and button changes
// `app.state` and hands it to the render path; committed changes become history
// entries (store.js), and Back and Forward walk through them.

import {
  PARAMS, couple, moveSlider, parseNumber, validate, writeControls,
} from "./controls.js";
import { onSchemeChange, setPresentation } from "../plots/draw.js";
import { addExportButtons, wireExports } from "../plots/export.js";
import {
  computeFramesAhead, redraw, refresh, settleNow,
} from "./render.js";
import { defaultState, fromQuery, presetState } from "./state.js";
import {
  $, app, commit, onIdle, setToggle, shownState,
} from "./store.js";
import { drawView, prefetchViews, viewFigures } from "./viewrequests.js";
import {
  pageFigures, requestViews, viewOfPlot,
} from "./views.js";

/** Show `state`: into the controls, the history (unless `push` is false), the plots. */
export function setState(state, { push = true } = {}) {
  app.state = state;
  writeControls(state);
  if (push) commit();
  refresh();
}

/** Every plot drawn again as the page is styled now (presentation mode, dark mode). */
function restyle() {
  if (!app.frame) return;
  redraw();
  for (const view of requestViews()) drawView(view.id);
}

/** The title of plot `plot` as its card names it (and its own name in a card of several). */
function plotTitle(plot) {
  const card = $(`plot-${plot}`).closest(".plot-card");
  const title = card.querySelector("h2, h3").textContent.trim();
  const picker = card.querySelectorAll(".plot").length > 1 && card.querySelector(`[aria-controls="plot-${plot}"]`);
  return picker ? `${title}: ${picker.textContent.trim().toLowerCase()}` : title;
}

/** What an export of plot `plot` needs (export.js): the figure shown now, plain, its
 *  title and its caption; null before the plot shows anything. */
function describePlot(plot) {
  const view = viewOfPlot(plot);
  const state = shownState();
  const figures = view.source === "frame" ? app.frame && pageFigures(app.frame, state, [plot]) : viewFigures(view.id, state);
  if (!figures?.[plot]) return null;
  return { name: plot, title: plotTitle(plot), caption: view.caption(state, plot), figure: figures[plot] };
}

/** Where a key moves a range input: one position, a tenth of the range, the ends (as
 *  the browser does; the page moves it itself, so that the plots follow at once). */
function keyTarget(key, range) {
  const value = Number(range.value);
  const min = Number(range.min);
  const max = Number(range.max);
  const tenth = Math.max(1, Math.round((max - min) / 10));
  const moves = {
    ArrowRight: value + 1, ArrowUp: value + 1, ArrowLeft: value - 1, ArrowDown: value - 1,
    PageUp: value + tenth, PageDown: value - tenth, Home: min, End: max,
  };
  return key in moves ? Math.min(max, Math.max(min, moves[key])) : null;
}

/** Keys move `range` in the page (keyTarget), then `moved()` and a history entry; on
 *  focus and after each press, once the page is idle, the states `ahead(direction)`
 *  gives (one press away, the way of the last press first) have their views' answers
 *  asked for and their live frames made, so that the next press either way waits for
 *  neither. */
export function wireSliderKeys(range, moved, ahead) {
  let direction = 1;
  const askAhead = () => onIdle(() => {
    const states = ahead(direction);
    prefetchViews(states);
    computeFramesAhead(states);
  });
  range.addEventListener("focus", askAhead);
  range.addEventListener("keydown", (event) => {
    if (event.altKey || event.ctrlKey || event.metaKey) return;
    const target = keyTarget(event.key, range);
    if (target === null) return;
    event.preventDefault();
    if (target !== Number(range.value)) {
      direction = Math.sign(target - Number(range.value));
      range.value = String(target);
      moved();
      commit();
    }
    askAhead();
  });
}

/** The states one key press away on `spec`'s slider, on either side, the one the way
 *  of `direction` (±1) first. */
function neighbours(spec, range, direction = 1) {
  const out = [];
  for (const step of [direction, -direction]) {
    const position = Number(range.value) + step;
    if (position < Number(range.min) || position > Number(range.max)) continue;
    const state = { ...app.state };
    moveSlider(state, spec, position);
    if (!Object.keys(validate(state)).length) out.push(state);
  }
  return out;
}

function wireParameters() {
  for (const spec of PARAMS) {
    const box = $(spec.name);
    const range = $(`${spec.name}-range`);
    const moved = () => {
      const coupled = moveSlider(app.state, spec, range.value);
      box.value = String(app.state[spec.name]);
      if (coupled) writeControls(app.state, { except: range });
      refresh({ hold: true });
    };
    range.addEventListener("input", moved);
    wireSliderKeys(range, moved, (direction) => neighbours(spec, range, direction));
    box.addEventListener("input", () => {
      const value = parseNumber(box.value);
      app.state[spec.name] = Number.isNaN(value) ? box.value : value;
      couple(app.state, spec.name);
      writeControls(app.state, { except: box });
      refresh({ hold: true });
    });
    for (const control of [range, box]) {
      control.addEventListener("change", () => {
        commit();
        settleNow();
      });
    }
  }
}

export function wireControls() {
  wireParameters();
  $("F_hat").addEventListener("change", () => {
    app.state.F_hat = $("F_hat").value;
    commit();
    refresh();
  });
  $("present").addEventListener("change", () => {
    setToggle("present", $("present").checked);
    setPresentation(app.state.present);
    commit();
    restyle();
  });
  onSchemeChange(restyle);
  $("preset").addEventListener("change", () => {
    const preset = app.presets.find((p) => p.name === $("preset").value);
    if (preset) setState(presetState(preset, app.defaults, app.state));
  });
  $("reset").addEventListener("click", () => setState(defaultState(app.defaults)));
  $("copy-link").addEventListener("click", async () => {
    // said under the button, where the person looks; where the clipboard is refused
    // (no permission, no secure context) the link is shown to copy by hand
    const status = $("copy-status");
    try {
      await navigator.clipboard.writeText(window.location.href);
      status.textContent = "Link copied.";
    } catch {
      status.textContent = `Copy this link: ${window.location.href}`;
    }
  });
  addExportButtons($("plots"));
  wireExports($("plots"), describePlot);
  window.addEventListener("popstate", () => {
    app.commitPending = false; // the entry walked to is the state now
    setState(fromQuery(window.location.search, app.defaults), { push: false });
  });
}
