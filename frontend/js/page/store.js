// The explorer's state in one place, and the signals that tell tests and scripts when
// the page has caught up with it:
//   #plots data-ready="true|false", data-frame=<count>, data-sim-ready="true|false";
//   window.breakaway.ready() / simReady() / rampReady() (main.js) wait on `waiting`.
// Every other explorer module reads and writes `app`; only this module flips the signals
// and writes the history entries (the URL holds every valid committed state).

import { validate } from "./controls.js";
import { toQuery } from "./state.js";

export const app = {
  defaults: null,
  presets: [],
  state: null,
  // the state the plots show while `state` is invalid (the last valid one: the plots keep
  // it, and what is on its way for it carries on), else null; `validCopy` a copy of the
  // last valid state (inputs change `state` in place)
  lastValid: null,
  validCopy: null,
  frame: null,
  frameKey: null, // the /api/explore body the frame answers
  liveOn: true, // live frames while a hand moves (off: every change drawn by Plotly)
  liveFrames: new Map(), // /api/explore body (JSON) -> its curves computed in the page
  liveRequest: null, // the animation frame that draws the next live frame
  holdUntil: 0, // the settled drawing waits until then (the hand is moving) [ms]
  lastInputAt: -Infinity, // the last input of a moving hand [ms]
  gaps: [], // the last gaps between its inputs [ms]
  settleTimer: null,
  frames: 0, // states shown, live or settled
  shownVersion: -1, // the state version the plots show
  version: 0, // each state change
  exploreController: null,
  busy: true,
  commitPending: false, // a history entry waits for its frame to be drawn
  lastRedrawMs: null,
  sim: null, // {key, k, u_ba, F_ba, t_ba}: `key` the /api/simulate body they answer
  lugre: null, // {k, u_ba, F_ba}
  simController: null,
  simTimer: null,
  simBusy: true, // until the first frame decides
  lugreController: null,
  results: {}, // view id -> {key, value}: the last answer of each view's own request
  cursor: null, // play: the time cursor [s]
  playing: null, // requestAnimationFrame id
  pinned: null, // plot id -> faded reference traces
  sweep: null, // {name, label, values, frames}
  tour: -1, // the tour's current step
  measured: null, // {plot, x, y}: the fitted data's points
};

const waiting = { ready: [], sim: [], views: [] };

export const $ = (id) => document.getElementById(id);

/** Set an element's text, attribute or `hidden` only when it changes: every key press
 *  writes them, and an unchanged write still makes the browser lay the page out anew
 *  (a text node replaced) or check its styles again. */
export function setText(element, text) {
  if (element.textContent !== text) element.textContent = text;
}

export function setAttr(element, name, value) {
  if (element.getAttribute(name) !== value) element.setAttribute(name, value);
}

export function setHidden(element, hidden) {
  if (element.hidden !== hidden) element.hidden = hidden;
}

/** Call `fn` once the browser is idle (after the frame on its way is drawn), at the
 *  latest after IDLE_WAIT_MS. */
const IDLE_WAIT_MS = 100;
export const onIdle = window.requestIdleCallback
  ? (fn) => window.requestIdleCallback(fn, { timeout: IDLE_WAIT_MS })
  : (fn) => setTimeout(fn, 1);

/** The state the plots and views show: the current one while it is valid, else the last
 *  valid one. */
export function shownState() {
  return app.lastValid ?? app.state;
}

/** Set a toggle (sim, lugre, present) in the state and in the state shown. */
export function setToggle(name, value) {
  app.state[name] = value;
  if (app.lastValid) app.lastValid[name] = value;
}

/** Resolve everything waiting for `kind` ("ready", "sim" or "views"). */
export function flush(kind) {
  const resolve = waiting[kind];
  waiting[kind] = [];
  for (const done of resolve) done();
}

/** A promise that resolves once `isBusy()` is false (checked now, then at each flush). */
export function whenIdle(kind, isBusy) {
  return new Promise((resolve) => {
    if (isBusy()) waiting[kind].push(resolve); else resolve();
  });
}

/** The plots are being brought up to date (busy) or show the current state. */
export function setBusy(busy) {
  app.busy = busy;
  if (!busy && app.frames > 0) $("loading").hidden = true;
  const plots = $("plots");
  setAttr(plots, "data-ready", busy ? "false" : "true");
  setAttr(plots, "data-frame", String(app.frames));
  setAttr(plots, "aria-busy", busy ? "true" : "false");
  if (busy) return;
  if (app.commitPending) setTimeout(writeHistory);
  else flush("ready");
}

/** Whether a simulation is due, waiting or running; flushes "sim" once none is. */
export function updateSimBusy() {
  // a frame on its way schedules the simulation when it is drawn
  const frameDue = app.busy && Boolean(app.state?.sim);
  app.simBusy = Boolean(app.simTimer || app.simController || app.lugreController || frameDue);
  setAttr($("plots"), "data-sim-ready", app.simBusy ? "false" : "true");
  if (!app.simBusy) flush("sim");
}

/** A history entry for the state, only when it is valid: a shared link never opens
 *  broken. Written in a task of its own once the frame is drawn: pushState costs a key
 *  press 1–4 ms (benchmarks/bench_page.py) that the plots should not wait for. */
export function commit() {
  app.commitPending = true;
  if (!app.busy) setTimeout(writeHistory);
}

function writeHistory() {
  if (!app.commitPending) return;
  app.commitPending = false;
  if (!Object.keys(validate(app.state)).length) {
    const query = toQuery(app.state);
    if (query !== window.location.search) window.history.pushState(null, "", query);
  }
  if (!app.busy) flush("ready");
}
