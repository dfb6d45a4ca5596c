// The explorer's one render path:
//   state → validate (MODEL.md §1) → one POST /api/explore (the previous one aborted)
//         → pure figure builders (the views of views.js) → the plots whose figure
//         changed (surfaces.js: Plotly.react, or the graph drawn ahead for this step).
// What hangs off a drawn frame (the simulations, the views with requests of their own)
// listens through onFrameDrawn / onStateLeft, so this module knows none of them.

import { ApiError, postJSON } from "./api.js";
import { moveSlider, showErrors, validate } from "./controls.js";
import { PLOT_CONFIG, pageStyle } from "./draw.js";
import { styled } from "./plots.js";
import { exploreBody, matchingPreset } from "./state.js";
import { $, app, setBusy, updateSimBusy } from "./store.js";
import { drawAhead, holds, show } from "./surfaces.js";
import { frameViewIds, pageFigures } from "./views.js";

/** The explorer's plots export through the page's own buttons (CSV, PNG). */
export const EXPLORER_CONFIG = {
  modeBarButtonsToRemove: [...PLOT_CONFIG.modeBarButtonsToRemove, "toImage"],
};

const listeners = { left: [], drawn: [] };

/** Call `fn()` whenever the state the page showed is left for another. */
export function onStateLeft(fn) {
  listeners.left.push(fn);
}

/** Call `fn()` once the frame of a new state is drawn. */
export function onFrameDrawn(fn) {
  listeners.drawn.push(fn);
}

function notify(kind) {
  for (const fn of listeners[kind]) fn();
}

/** The state changed: draw it (or show why it cannot be). */
export function refresh() {
  const errors = validate(app.state);
  showErrors(errors);
  hideServerError();
  updatePresetSelect();
  app.version += 1;
  const version = app.version;
  if (app.exploreController) app.exploreController.abort();
  app.exploreController = null;
  if (Object.keys(errors).length) {
    notify("left");
    $("plots").dataset.valid = "false";
    setBusy(false);
    updateSimBusy();
    return;
  }
  $("plots").dataset.valid = "true";
  const controller = new AbortController();
  app.exploreController = controller;
  setBusy(true);
  // the pending simulations are for the state just left: drop them now, so they do not
  // compete with this frame (they are scheduled again once it is drawn)
  notify("left");
  const started = performance.now();
  const body = exploreBody(app.state);
  const key = JSON.stringify(body);
  // a change the model's curves do not depend on (the mass m) needs no new frame
  const frameAsked = app.frame && key === app.frameKey
    ? Promise.resolve(app.frame)
    : frameFor(body, key, controller.signal);
  frameAsked
    .then(async (frame) => {
      if (version !== app.version) return;
      app.frame = frame;
      app.frameKey = key;
      await redraw();
      if (version !== app.version) return;
      app.frames += 1;
      app.lastRedrawMs = performance.now() - started;
      app.exploreController = null;
      setBusy(false);
      notify("drawn");
      prefetchNextStep();
    })
    .catch((error) => {
      if (error.name === "AbortError" || version !== app.version) return;
      app.exploreController = null;
      showServerError(error);
      setBusy(false);
      updateSimBusy();
    });
}

/** The frame for an explore body: the one asked for ahead of this key press when there
 *  is one (a failed one is asked for again), else a new request. */
function frameFor(body, key, signal) {
  const { ahead } = app;
  app.ahead = null;
  if (ahead?.key !== key) return postJSON("/api/explore", body, signal);
  app.prefetchHits += 1;
  return ahead.asked.catch(() => postJSON("/api/explore", body, signal));
}

/**
 * A person stepping a slider with the arrow keys presses the same key again: ask for
 * that next position's frame now, at low priority, so the key press finds it here and
 * waits only for the drawing (benchmarks/bench_page.py: about a fifth of a key press).
 * One request per drawn frame, and only while a slider has the keyboard.
 */
function prefetchNextStep() {
  const last = app.lastStep;
  const range = document.activeElement;
  if (!app.prefetchOn || !last || range?.id !== `${last.spec.name}-range`) return;
  const position = Number(range.value) + last.step;
  if (position < Number(range.min) || position > Number(range.max)) return;
  const next = { ...app.state };
  moveSlider(next, last.spec, position);
  if (Object.keys(validate(next)).length) return;
  const body = exploreBody(next);
  const key = JSON.stringify(body);
  // a step the quasi-static curves do not see (the mass m) needs no frame
  if (key === app.frameKey) return;
  const asked = postJSON("/api/explore", body, undefined, "low");
  const ahead = { key, asked, state: next, frame: null };
  app.ahead = ahead;
  // a failed one is asked for again when its key is pressed
  asked.then((frame) => {
    ahead.frame = frame;
    scheduleDrawAhead();
  }, () => {});
}

/** Draw the next arrow step's plots into the hidden graphs while the page has nothing
 *  else to do, one plot per task (a key press waits for one at most); and again when
 *  what they would show changed (a simulation came in, the style changed). */
function scheduleDrawAhead() {
  if (!app.drawAheadOn || app.aheadTimer) return;
  app.aheadTimer = setTimeout(drawNextAhead);
}

function drawNextAhead() {
  app.aheadTimer = null;
  const { ahead } = app;
  // while busy, the frame being drawn asks for its own next step; while playing, the
  // phase plot changes every animation frame
  if (app.busy || app.playing || !ahead?.frame || ahead !== app.ahead) return;
  const figs = aheadFigures();
  for (const id of frameViewIds()) {
    const drawing = drawAhead(id, figs[id], EXPLORER_CONFIG);
    if (drawing) {
      // a graph that failed to draw ahead is drawn when it is needed
      drawing.then(scheduleDrawAhead, () => {});
      return;
    }
  }
}

/** The next arrow step's figures, styled as the page is shown now (null until its
 *  frame is here). */
function aheadFigures() {
  const { ahead } = app;
  if (!ahead?.frame) return null;
  const figs = pageFigures(ahead.frame, ahead.state);
  return Object.fromEntries(frameViewIds().map((id) => [id, styled(figs[id], pageStyle())]));
}

/** True once the next arrow step's plots are drawn (ahead, or already shown). */
export function aheadDrawn() {
  const figs = aheadFigures();
  return Boolean(figs) && frameViewIds().every((id) => holds(id, figs[id]));
}

/** Show a figure on plot `id`, styled as the page is shown now; what is left drawn
 *  ahead may no longer be what the next step shows. */
export function showPlot(id, plain) {
  return show(id, styled(plain, pageStyle()), EXPLORER_CONFIG).then(scheduleDrawAhead);
}

/** Draw the current frame's views (all, or those in `ids`). */
export function redraw(ids = frameViewIds()) {
  if (!app.frame) return Promise.resolve();
  const figs = pageFigures(app.frame, app.state, ids);
  return Promise.all(ids.map((id) => showPlot(id, figs[id])));
}

function updatePresetSelect() {
  const name = matchingPreset(app.state, app.presets);
  $("preset").value = name;
  const preset = app.presets.find((p) => p.name === name);
  $("preset-description").textContent = preset ? preset.description : "";
  // the note's s = 1 scaling: say so wherever these numbers are read
  $("units-note").hidden = !(preset ? preset.units === "normalised" : Number(app.state.s) === 1);
}

export function showServerError(error) {
  const fields = error instanceof ApiError ? error.fieldErrors() : {};
  if (Object.keys(fields).length) {
    showErrors(fields);
    return;
  }
  const box = $("server-error");
  // an answer from the server, or a failure to reach it or to draw what it sent
  const what = error instanceof ApiError || error instanceof TypeError && /fetch/i.test(error.message)
    ? "The server could not compute this view" : "The page could not draw this view";
  box.textContent = `${what}: ${error.message}`;
  box.hidden = false;
}

function hideServerError() {
  $("server-error").hidden = true;
}
