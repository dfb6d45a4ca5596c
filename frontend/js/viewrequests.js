// The views that draw the answer of a request of their own (views.js: `request`), such
// as the ramp experiment: asked for once a state's frame is drawn, after the view's
// debounce, the previous request aborted; an answer for the state shown is not asked
// for again. Each answer drawn counts in #plots data-<id>-frame.

import { postJSON } from "./api.js";
import { onFrameDrawn, onStateLeft, redraw, showPlot } from "./render.js";
import { $, app, flush } from "./store.js";
import { requestViews, viewOf } from "./views.js";

const runs = {}; // view id -> {timer, controller, frames}

function run(id) {
  runs[id] ??= { timer: null, controller: null, frames: 0 };
  return runs[id];
}

function keyOf(view, state) {
  return JSON.stringify(view.request.body(state));
}

/** The last answer of view `id` and whether it is for another state than `state`. */
export function viewResult(id, state) {
  const result = app.results[id];
  if (!result) return null;
  return { value: result.value, stale: result.key !== keyOf(viewOf(id), state) };
}

/** True while a view's request is due or on its way. */
export function viewsBusy() {
  return Object.values(runs).some((entry) => entry.timer || entry.controller);
}

function cancel(view) {
  const entry = run(view.id);
  clearTimeout(entry.timer);
  entry.timer = null;
  if (entry.controller) entry.controller.abort();
  entry.controller = null;
  if (!viewsBusy()) flush("views");
}

function schedule(view) {
  if (!app.frame) return;
  const result = app.results[view.id];
  if (result && result.key === keyOf(view, app.state)) {
    drawView(view.id);
    return;
  }
  const entry = run(view.id);
  clearTimeout(entry.timer);
  entry.timer = setTimeout(() => ask(view), view.request.debounceMs ?? 0);
}

async function ask(view) {
  const entry = run(view.id);
  entry.timer = null;
  if (entry.controller) entry.controller.abort();
  const controller = new AbortController();
  entry.controller = controller;
  const key = keyOf(view, app.state);
  try {
    const value = await postJSON(view.request.url, view.request.body(app.state), controller.signal);
    if (controller !== entry.controller) return;
    app.results[view.id] = { key, value };
    view.onResult?.(value);
    await drawView(view.id);
    entry.frames += 1;
    $("plots").dataset[`${view.id}Frame`] = String(entry.frames);
  } catch (error) {
    if (error.name === "AbortError" || controller !== entry.controller) return;
    view.onError?.(error);
  }
  if (controller === entry.controller) {
    entry.controller = null;
    if (!viewsBusy()) flush("views");
  }
}

/** Draw view `id` from its last answer, and the frame views that show it too. */
export function drawView(id) {
  const view = viewOf(id);
  const result = app.results[id];
  if (!result || !app.frame) return Promise.resolve();
  view.onDraw?.(result.value, app.state);
  const figure = view.figure({ frame: app.frame, state: app.state, result: result.value });
  return Promise.all([showPlot(id, figure), redraw(view.redraws ?? [])]);
}

// a request for the state just left is dropped; the new state's is asked for once its
// frame is drawn
onStateLeft(() => requestViews().forEach(cancel));
onFrameDrawn(() => requestViews().forEach(schedule));
