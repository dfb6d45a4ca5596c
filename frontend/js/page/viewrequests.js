// The views that draw the answer of a request of their own (views.js: `request`), such
// as the ramp experiment. Two ways to be asked:
//   settled  once a state's frame is settled, after the view's debounce, the previous
//            request aborted (a slider that moves the model's curves: the view follows
//            when the hand stops, as the simulations do);
//   live     at the next animation frame, for the state then, when a change leaves the
//            model's curves as they are (the mass m): then this view is what the hand
//            explores (a drag's two or three inputs a frame under a slow processor ask
//            once, not each for a run and a drawing). Two requests in flight at most,
//            none aborted (a drag never starves); a hand that moved on meanwhile is asked
//            for when one lands; an answer older than the one shown is dropped.
// A key press asks ahead for the answers one press away on either side. An answer for
// the state shown is not asked for again. A view that can compute its answer in the page
// (request.local(body): the same model as the server's, a value or a promise of one, or
// null when that would take too long) asks the server only when the page cannot. Each
// answer drawn counts in #plots data-<id>-frame.

import { postJSON } from "./api.js";
import {
  beforeSettle, drawLiveNow, onFrameDrawn, onStateLeft, redraw, showPlot,
} from "./render.js";
import { exploreBody } from "./state.js";
import {
  $, app, flush, shownState, whenIdle,
} from "./store.js";
import { requestViews, viewOf } from "./views.js";

const KEPT = 8;
/** Live requests of one view on their way at a time: two, so that an input waits for
 *  one round trip, not for the end of the one before it too. */
const LIVE_FLYING = 2;
const runs = {}; // view id -> {timer, controller, key (asked for), again, frames}
const ahead = new Map(); // "<view id> <key>" -> the answer asked for ahead of a key press
const answers = new Map(); // "<view id> <key>" -> an answer drawn lately (a turn goes back to it)

function keep(map, name, value) {
  map.delete(name);
  map.set(name, value);
  if (map.size > KEPT) map.delete(map.keys().next().value);
}

function run(id) {
  // flying: request number -> {controller, key}; shown: the number of the answer shown;
  // drawn: the key of the answer last drawn
  runs[id] ??= {
    timer: null, soon: null, flying: new Map(), count: 0, shown: 0, again: false, frames: 0, drawn: null,
  };
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
  return Object.values(runs).some((entry) => entry.timer || entry.soon || entry.flying.size);
}

function flying(entry, key) {
  return [...entry.flying.values()].some((request) => request.key === key);
}

function abortFlying(entry) {
  for (const request of entry.flying.values()) request.controller.abort();
  entry.flying.clear();
}

function cancel(view) {
  const entry = run(view.id);
  clearTimeout(entry.timer);
  entry.timer = null;
  cancelAnimationFrame(entry.soon);
  entry.soon = null;
  entry.again = false;
  abortFlying(entry);
  if (!viewsBusy()) flush("views");
}

function answerFor(view, key, body, signal) {
  const name = `${view.id} ${key}`;
  if (answers.has(name)) return Promise.resolve(answers.get(name));
  const server = () => {
    const asked = ahead.get(name);
    if (!asked) return postJSON(view.request.url, body, signal);
    ahead.delete(name);
    return asked.catch(() => postJSON(view.request.url, body, signal));
  };
  // the page's own run (a value, or a promise of one), or null: the server's, which
  // also makes it when the page's failed (and says why, where the body is wrong)
  let local = null;
  try {
    local = view.request.local?.(body) ?? null;
  } catch {
    local = null;
  }
  return local ? Promise.resolve(local).then((value) => value ?? server()) : server();
}

/** Ask for `state`'s answer and draw it, unless a later request's answer is shown by
 *  then; `live` requests run beside one another (a drag), the others replace them. */
async function ask(view, state, { live = false } = {}) {
  const entry = run(view.id);
  if (!live) abortFlying(entry);
  const controller = new AbortController();
  const key = keyOf(view, state);
  entry.count += 1;
  const number = entry.count;
  entry.flying.set(number, { controller, key });
  entry.again = false;
  try {
    const value = await answerFor(view, key, view.request.body(state), controller.signal);
    if (entry.flying.has(number) && number > entry.shown) {
      entry.shown = number;
      app.results[view.id] = { key, value };
      keep(answers, `${view.id} ${key}`, value);
      view.onResult?.(value);
      // on its canvas at once, counted, then settled by Plotly when the page is
      const settling = drawView(view.id, { now: true });
      entry.frames += 1;
      $("plots").dataset[`${view.id}Frame`] = String(entry.frames);
      await settling;
    }
  } catch (error) {
    if (error.name !== "AbortError" && entry.flying.has(number)) view.onError?.(error);
  }
  if (entry.flying.delete(number)) {
    if (entry.again) askNow(view);
    if (!viewsBusy()) flush("views");
  }
}

/** Ask at the next animation frame for the state then (askNow). */
function askLive(view) {
  const entry = run(view.id);
  clearTimeout(entry.timer);
  entry.timer = null;
  entry.soon ??= requestAnimationFrame(() => {
    entry.soon = null;
    askNow(view);
    if (!viewsBusy()) flush("views");
  });
}

/** Ask for the current state, unless its answer is here or on its way: at most
 *  LIVE_FLYING requests at a time, then the state the hand is on when one lands. */
function askNow(view) {
  const entry = run(view.id);
  const state = shownState();
  const key = keyOf(view, state);
  entry.again = false;
  if (app.results[view.id]?.key === key) {
    // a change this view does not depend on (the loop's gains for the ramp) draws nothing
    if (entry.drawn !== key) drawView(view.id);
  } else if (flying(entry, key)) return;
  else if (entry.flying.size < LIVE_FLYING) ask(view, state, { live: true });
  else entry.again = true;
}

/** Once a state's frame is settled: its answer drawn, or asked for after the debounce. */
function schedule(view) {
  if (!app.frame) return;
  const state = shownState();
  const key = keyOf(view, state);
  const entry = run(view.id);
  if (app.results[view.id]?.key === key) {
    drawView(view.id);
    return;
  }
  if (entry.flying.size) {
    // live requests (the mass moved) land first, then the state shown is asked for
    entry.again = !flying(entry, key);
    return;
  }
  clearTimeout(entry.timer);
  entry.timer = setTimeout(() => {
    entry.timer = null;
    ask(view, shownState());
  }, view.request.debounceMs ?? 0);
}

/** Ask ahead, at low priority, for the answers of `states` (a key press away) that only
 *  the views' requests can draw (their model curves are the ones shown), or that a view
 *  drawn live at every change (request.live) draws. */
export function prefetchViews(states) {
  for (const view of requestViews()) {
    for (const state of states) {
      if (JSON.stringify(exploreBody(state)) !== app.frameKey && !view.request.live?.(state)) continue;
      const key = keyOf(view, state);
      const name = `${view.id} ${key}`;
      if (answers.has(name) || ahead.has(name) || view.request.local) continue;
      const asked = postJSON(view.request.url, view.request.body(state), undefined, "low");
      asked.catch(() => {}); // a failed one is asked for again when its key is pressed
      keep(ahead, name, asked);
    }
  }
}

/** The figures view `id` shows for its last answer, {plot id: figure} (a view may draw
 *  several plots from one answer: figures(ctx)), or null before its first answer. */
export function viewFigures(id, state = shownState()) {
  const view = viewOf(id);
  const result = app.results[id];
  if (!result || !app.frame) return null;
  const ctx = { frame: app.frame, state, result: result.value };
  return view.figures ? view.figures(ctx) : { [id]: view.figure(ctx) };
}

/** Draw view `id` from its last answer, and the frame views that show it too; `now`:
 *  first at once on the live canvases, Plotly in a task of its own. */
export function drawView(id, { now = false } = {}) {
  const view = viewOf(id);
  const result = app.results[id];
  if (!result || !app.frame) return Promise.resolve();
  run(id).drawn = result.key;
  const state = shownState();
  const shown = viewFigures(id, state);
  const settled = () => Promise.all([
    ...Object.entries(shown).map(([plot, figure]) => showPlot(plot, figure)),
    redraw(view.redraws ?? [])]);
  // first on the live canvases at once, then Plotly in a task of its own; the view's
  // words after its plots: a canvas's first text after a change to the page's text waits
  // for the page's styles to be recomputed (0.7 ms, once a canvas)
  const drawnLive = now && Object.entries(shown).map(([plot, figure], i) => drawLiveNow(plot,
    figure, i === 0 ? view.redraws ?? [] : [])).every(Boolean);
  view.onDraw?.(result.value, state);
  if (!drawnLive) return settled();
  return new Promise((resolve) => { setTimeout(() => settled().then(resolve, resolve)); });
}

// a request for a state whose curves were left is dropped (the new state's is asked for
// once its frame is settled); when the curves stay, the views are what moved
onStateLeft(({ frameChanged }) => {
  for (const view of requestViews()) {
    // a view quick enough to answer (request.live(state) true) follows every change live
    if (frameChanged && !view.request.live?.(shownState())) cancel(view); else askLive(view);
  }
});
onFrameDrawn(() => requestViews().forEach(schedule));
// live answers on their way (the mass moved) land before Plotly draws the settled plots
beforeSettle(() => whenIdle("views", viewsBusy));
