// The explorer's one render path:
//   state → validate (the model's constraints) → a frame → pure figure builders (the views of
//   views.js) → the plots, in two steps:
//   live     at the next animation frame, the model's curves computed in the page
//            (model.js) drawn on a canvas in each plot's own axes (surfaces.js): what a
//            hand on a slider sees, 30 and more frames a second;
//   settled  once the hand stops (at once for a menu, a preset, a released slider): one
//            POST /api/explore (the previous one aborted), drawn by Plotly.react, one
//            plot per task so that a key or a pointer can come in between.
// `#plots` data-frame counts the states shown (live or settled), data-ready="true" says
// the settled plots show the current state. What hangs off a settled frame (the
// simulations, the views with requests of their own) listens through onFrameDrawn and
// onStateLeft, so this module knows none of them.

import { ApiError, postJSON } from "./api.js";
import { showErrors, validate } from "./controls.js";
import { PLOT_CONFIG, pageStyle } from "../plots/draw.js";
import { modelFrame } from "../models/model.js";
import { styled } from "../plots/plots.js";
import { exploreBody, matchingPreset } from "./state.js";
import {
  $, app, onIdle, setAttr, setBusy, setHidden, setText, shownState, updateSimBusy,
} from "./store.js";
import { live, prepare, settle } from "../plots/surfaces.js";
import { frameViewIds, pageFigures } from "./views.js";

/** The explorer's plots export through the page's own buttons (CSV, PNG). */
export const EXPLORER_CONFIG = {
  modeBarButtonsToRemove: [...PLOT_CONFIG.modeBarButtonsToRemove, "toImage"],
};
/** A hand that gives no input for this long has stopped [ms]: a held arrow key repeats
 *  every 33 ms, a drag's inputs come every 16 ms. A person pressing keys one by one (gaps
 *  under RHYTHM_MS) has stopped once 1.5 times the longest of their last gaps passes
 *  without a press, up to HOLD_MAX_MS: a press that lands on the settled drawing waits
 *  for one Plotly.react (13–24 ms). */
export const SETTLE_MS = 250;
const RHYTHM_MS = 1000;
const HOLD_MAX_MS = 750;
const GAPS_KEPT = 3;

const listeners = { left: [], drawn: [], before: [], ahead: [] };

/** Call `fn({frameChanged})` whenever the state the page showed is left for another;
 *  `frameChanged` false when the model's curves stay (the mass m moved). */
export function onStateLeft(fn) {
  listeners.left.push(fn);
}

/** Call `fn()` once the frame of a new state is drawn and settled. */
export function onFrameDrawn(fn) {
  listeners.drawn.push(fn);
}

/** Call `fn()` before a settled drawing, which waits for the promise it returns (the
 *  answers of views on their way, so that Plotly draws them once, not twice). */
export function beforeSettle(fn) {
  listeners.before.push(fn);
}

/** Call `fn(state)` while the page is idle for each state one key press away, so that
 *  what a view derives from the state for its live frame is made before the press. */
export function onComputeAhead(fn) {
  listeners.ahead.push(fn);
}

function notify(kind, detail) {
  for (const fn of listeners[kind]) fn(detail);
}

const nextTask = () => new Promise((resolve) => { setTimeout(resolve); });

/**
 * The state changed: draw it (or show why it cannot be). `hold`: the change comes from
 * a moving hand (a slider, a key, typing), so the settled drawing waits until it stops.
 */
export function refresh({ hold = false } = {}) {
  const errors = validate(app.state);
  showErrors(errors);
  hideServerError();
  updatePresetSelect();
  if (Object.keys(errors).length) {
    // the plots keep the last valid state, and what is on its way for it (its settled
    // frame, the ramp and the loop, their sentences) carries on
    setAttr($("plots"), "data-valid", "false");
    app.lastValid ??= app.validCopy;
    if (!app.settleTimer && !app.exploreController) setBusy(false);
    updateSimBusy();
    return;
  }
  app.lastValid = null;
  app.validCopy = { ...app.state };
  app.version += 1;
  clearTimeout(app.settleTimer);
  app.settleTimer = null;
  if (app.exploreController) app.exploreController.abort();
  app.exploreController = null;
  setAttr($("plots"), "data-valid", "true");
  const frameChanged = JSON.stringify(exploreBody(app.state)) !== app.frameKey;
  setBusy(true);
  // the pending simulations are for the state just left: drop them now, so they do not
  // compete with this frame (they are scheduled again once it is settled)
  notify("left", { frameChanged });
  app.holdUntil = hold && app.liveOn ? performance.now() + holdFor(performance.now()) : 0;
  if (app.liveOn && app.frames > 0 && !app.liveRequest) {
    app.liveRequest = requestAnimationFrame(drawLiveFrame);
  }
  settleLater(app.version);
}

/** How long the settled drawing waits after an input at `now` [ms]. */
function holdFor(now) {
  const gap = now - app.lastInputAt;
  app.lastInputAt = now;
  app.gaps = gap < RHYTHM_MS ? [...app.gaps, gap].slice(-GAPS_KEPT) : [];
  return Math.min(Math.max(SETTLE_MS, 1.5 * Math.max(0, ...app.gaps)), HOLD_MAX_MS);
}

/** The hand has stopped (a slider released, a number box left): settle now. */
export function settleNow() {
  if (!app.holdUntil) return;
  app.holdUntil = 0;
  if (app.settleTimer) settleLater(app.version);
}

function settleLater(version) {
  clearTimeout(app.settleTimer);
  app.settleTimer = null;
  const wait = app.holdUntil - performance.now();
  if (wait > 0) app.settleTimer = setTimeout(() => settleLater(version), wait);
  else settleFrame(version);
}

/** Curves kept for live frames: the current state's and those one key press away. */
const LIVE_FRAMES_KEPT = 4;

function keepLiveFrame(key, frame) {
  app.liveFrames.delete(key);
  app.liveFrames.set(key, frame);
  if (app.liveFrames.size > LIVE_FRAMES_KEPT) app.liveFrames.delete(app.liveFrames.keys().next().value);
  return frame;
}

/** The curves of `state` for a live frame: the server's frame when it is for these
 *  curves already (only m moved), else computed here (or ahead, below). */
function liveFrame(state = shownState()) {
  const body = exploreBody(state);
  const key = JSON.stringify(body);
  if (app.frame && key === app.frameKey) return app.frame;
  return keepLiveFrame(key, app.liveFrames.get(key) ?? modelFrame(body));
}

let ahead = []; // what is to be made while the page is idle, in small tasks
/** An idle moment takes tasks ahead while this much of it is left [ms]: a task takes
 *  1–5 ms under a phone's processor, and a key that comes meanwhile waits for it. */
const AHEAD_ROOM_MS = 10;

function workAhead(deadline) {
  do {
    const task = ahead.shift();
    if (!task) return;
    task();
  } while (ahead.length && deadline?.timeRemaining() > AHEAD_ROOM_MS);
  if (ahead.length) onIdle(workAhead);
}

/** The tasks that make the live frame of `state` ahead: its curves (and what views
 *  derive from the state, onComputeAhead), then its figures, then each plot's frame
 *  painted (surfaces.prepare), so that a press that reaches it only copies them. */
function tasksAhead(state) {
  let figures = null;
  const tasks = [() => {
    liveFrame(state);
    notify("ahead", state);
  }];
  if (!app.liveOn || app.frames === 0) return tasks;
  tasks.push(() => { figures = liveFigures(state); });
  for (const id of frameViewIds()) tasks.push(() => prepare(id, figures[id]));
  return tasks;
}

/** The styled figures a live frame of `state` draws, by plot id: one builder for the
 *  frame a press draws and the one painted ahead for it, which it copies only when
 *  the two are equal. */
function liveFigures(state = shownState()) {
  const style = pageStyle();
  const figs = pageFigures(liveFrame(state), state);
  return Object.fromEntries(frameViewIds().map((id) => [id, styled(figs[id], style)]));
}

/** Make the live frames of `states` (one key press away) while the page is idle, so
 *  that the press finds them made and its live frame only copies them: the model's
 *  curves took a fifth of a frame under a phone's processor, the drawing the half. */
export function computeFramesAhead(states) {
  const waiting = ahead.length > 0;
  ahead = states.filter((state) => !Object.keys(validate(state)).length).flatMap(tasksAhead);
  if (!waiting && ahead.length) onIdle(workAhead);
}

function drawLiveFrame() {
  app.liveRequest = null;
  const version = app.version;
  if (!app.busy || app.shownVersion === version) return;
  for (const [id, figure] of Object.entries(liveFigures())) live(id, figure);
  app.shownVersion = version;
  app.frames += 1;
  $("plots").dataset.frame = String(app.frames);
}

/** True between a state change and its settle, while live frames are on (a request
 *  view's answer that comes meanwhile is drawn live too). */
function showingLive() {
  return app.busy && app.liveOn && app.frames > 0;
}

function settleFrame(version) {
  const started = performance.now();
  const body = exploreBody(shownState());
  const key = JSON.stringify(body);
  const controller = new AbortController();
  app.exploreController = controller;
  // a change the model's curves do not depend on (the mass m) needs no new frame
  const asked = app.frame && key === app.frameKey
    ? Promise.resolve(app.frame)
    : postJSON("/api/explore", body, controller.signal);
  asked
    .then(async (frame) => {
      await Promise.all(listeners.before.map((fn) => fn()));
      if (version !== app.version) return;
      app.frame = frame;
      app.frameKey = key;
      if (!await drawSettled(version) || version !== app.version) return;
      if (app.shownVersion !== version) {
        app.shownVersion = version;
        app.frames += 1;
      }
      app.lastRedrawMs = performance.now() - started;
      app.exploreController = null;
      setBusy(false);
      notify("drawn");
    })
    .catch((error) => {
      if (error.name === "AbortError" || version !== app.version) return;
      app.exploreController = null;
      showServerError(error);
      setBusy(false);
      updateSimBusy();
    });
}

/** Plotly draws the current frame's views; between two plots a key or a pointer may
 *  come (then false: a newer state is on its way). */
async function drawSettled(version) {
  const figs = pageFigures(app.frame, shownState());
  const ids = frameViewIds();
  if (!app.liveOn || app.frames === 0) {
    await Promise.all(ids.map((id) => showPlot(id, figs[id])));
    return version === app.version;
  }
  for (const id of ids) {
    await nextTask();
    if (version !== app.version) return false;
    await settle(id, styled(figs[id], pageStyle()), EXPLORER_CONFIG, () => version === app.version);
  }
  return version === app.version;
}

/** Show a figure on plot `id`, styled as the page is shown now: live while the plots
 *  show a live frame, else with Plotly. */
export function showPlot(id, plain) {
  const figure = styled(plain, pageStyle());
  if (showingLive() && live(id, figure)) return Promise.resolve();
  return settle(id, figure, EXPLORER_CONFIG);
}

/** Draw a view's figure on its live canvas at once, and the frame views in `ids` that
 *  show its answer too, when live frames are on (the settled drawing may follow); true
 *  when drawn. */
export function drawLiveNow(id, plain, ids = []) {
  if (!app.liveOn || app.frames === 0 || !app.frame) return false;
  const done = live(id, styled(plain, pageStyle()));
  const figs = pageFigures(app.busy ? liveFrame() : app.frame, shownState(), ids);
  for (const other of ids) live(other, styled(figs[other], pageStyle()));
  return done;
}

/** Draw the current frame's views again (all, or those in `ids`): a simulation came,
 *  the style or an overlay changed. */
export function redraw(ids = frameViewIds()) {
  if (!app.frame) return Promise.resolve();
  const figs = pageFigures(showingLive() ? liveFrame() : app.frame, shownState(), ids);
  return Promise.all(ids.map((id) => showPlot(id, figs[id])));
}

function updatePresetSelect() {
  const name = matchingPreset(app.state, app.presets);
  if ($("preset").value !== name) $("preset").value = name;
  const preset = app.presets.find((p) => p.name === name);
  setText($("preset-description"), preset ? preset.description : "");
  // the note's s = 1 scaling: say so wherever these numbers are read
  setHidden($("units-note"), !(preset ? preset.units === "normalised" : Number(app.state.s) === 1));
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
  setHidden($("server-error"), true);
}
