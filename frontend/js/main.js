// The explorer page. One render path:
//   state → validate (MODEL.md §1) → one POST /api/explore (the previous one aborted)
//         → pure figure builders (plots.js) → the plots whose figure changed
//         (surfaces.js: Plotly.react, or the graph drawn ahead for this arrow step).
// The simulations run beside it, debounced and abortable, and redraw only the plots
// that show them, so they never hold up a slider.
//
// For tests and scripts: #plots carries data-ready="true|false" and data-frame=<count>;
// window.breakaway.ready() resolves once the plots show the current state (or its
// inline errors), window.breakaway.simReady() once the simulation points are settled.

import { ApiError, getJSON, postJSON } from "./api.js";
import {
  PARAMS, buildControls, paramSpec, parseNumber, setParams, showErrors, sliderToValue,
  validate, writeControls,
} from "./controls.js";
import { fitReady, fitReport, initDataPanel } from "./datapanel.js";
import { exportCsv, exportPng } from "./export.js";
import { PLOT_CONFIG, onSchemeChange, pageStyle } from "./draw.js";
import { PLOT_IDS, figures, styled } from "./plots.js";
import {
  explainBreakaway, rampBody, rampFigure, simulationPhaseTrace,
} from "./ramp.js";
import {
  TOUR, pinnedTraces, sweepTraces, sweepValues, tourState, withTraces,
} from "./teach.js";
import {
  defaultState, exploreBody, fromQuery, matchingPreset, presetState, simulateBody, toQuery,
} from "./state.js";
import { addAheadGraphs, drawAhead, holds, show, surfaceStats } from "./surfaces.js";

const SIM_DEBOUNCE_MS = 350;
const RAMP_DEBOUNCE_MS = 60;
const PLAY_SECONDS = 4;
/** Arrow keys on a focused slider: one position up or down. */
const KEY_STEP = { ArrowRight: 1, ArrowUp: 1, ArrowLeft: -1, ArrowDown: -1 };
/** The explorer's plots export through the page's own buttons (CSV, PNG). */
const EXPLORER_CONFIG = { modeBarButtonsToRemove: [...PLOT_CONFIG.modeBarButtonsToRemove, "toImage"] };

const app = {
  defaults: null,
  presets: [],
  state: null,
  frame: null,
  frameKey: null, // the /api/explore body the frame answers
  ahead: null, // {key, asked, state, frame}: the next arrow step, its /api/explore body
  // and the answer asked for (the frame once it is here)
  prefetchOn: true,
  drawAheadOn: true,
  aheadTimer: null, // the next plot to draw ahead
  prefetchHits: 0,
  lastStep: null, // {spec, step}: the last arrow key on a slider
  frames: 0,
  version: 0,
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
  ramp: null, // the last /api/ramp answer, with its key
  rampKey: null,
  rampController: null,
  rampTimer: null,
  rampFrames: 0, // ramp experiments drawn
  cursor: null, // play: the time cursor [s]
  playing: null, // requestAnimationFrame id
  pinned: null, // plot id -> faded reference traces
  sweep: null, // {name, label, values, frames}
  tour: -1, // the tour's current step
  measured: null, // {plot, x, y}: the fitted data's points
};

const waiting = { ready: [], sim: [], ramp: [] };
const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------------------------
// status signals
// ---------------------------------------------------------------------------------

function setBusy(busy) {
  app.busy = busy;
  if (!busy && app.frames > 0) $("loading").hidden = true;
  const plots = $("plots");
  plots.dataset.ready = busy ? "false" : "true";
  plots.dataset.frame = String(app.frames);
  plots.setAttribute("aria-busy", busy ? "true" : "false");
  if (busy) return;
  if (app.commitPending) setTimeout(writeHistory);
  else flush("ready");
}

function updateSimBusy() {
  // a frame on its way schedules the simulation when it is drawn
  const frameDue = app.busy && Boolean(app.state?.sim) && Boolean(app.exploreController || app.frames === 0);
  app.simBusy = Boolean(app.simTimer || app.simController || app.lugreController || frameDue);
  $("plots").dataset.simReady = app.simBusy ? "false" : "true";
  if (!app.simBusy) flush("sim");
}

function flush(kind) {
  const resolve = waiting[kind];
  waiting[kind] = [];
  for (const done of resolve) done();
}

function whenIdle(kind, isBusy) {
  return new Promise((resolve) => {
    if (isBusy()) waiting[kind].push(resolve); else resolve();
  });
}

// ---------------------------------------------------------------------------------
// the render path
// ---------------------------------------------------------------------------------

function refresh() {
  const errors = validate(app.state);
  showErrors(errors);
  hideServerError();
  updatePresetSelect();
  app.version += 1;
  const version = app.version;
  if (app.exploreController) app.exploreController.abort();
  app.exploreController = null;
  if (Object.keys(errors).length) {
    cancelSim();
    cancelRamp();
    $("plots").dataset.valid = "false";
    setBusy(false);
    updateSimBusy();
    return;
  }
  $("plots").dataset.valid = "true";
  const controller = new AbortController();
  app.exploreController = controller;
  setBusy(true);
  // the pending simulation and ramp are for the state just left: drop them now, so they
  // do not compete with this frame (they are scheduled again once it is drawn)
  cancelSim();
  cancelRamp();
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
      await draw();
      if (version !== app.version) return;
      app.frames += 1;
      app.lastRedrawMs = performance.now() - started;
      app.exploreController = null;
      setBusy(false);
      scheduleSim();
      scheduleRamp();
      ensureLugre();
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
  for (const id of PLOT_IDS) {
    const drawing = drawAhead(id, figs[id], EXPLORER_CONFIG);
    if (drawing) {
      // a graph that failed to draw ahead is drawn when it is needed
      drawing.then(scheduleDrawAhead, () => {});
      return;
    }
  }
}

/** The next arrow step's four figures, styled as the page is shown now (null until its
 *  frame is here). */
function aheadFigures() {
  const { ahead } = app;
  if (!ahead?.frame) return null;
  const figs = pageFigures(ahead.frame, ahead.state);
  return Object.fromEntries(PLOT_IDS.map((id) => [id, styled(figs[id], pageStyle())]));
}

/** Show a figure on plot `id`, styled as the page is shown now; what is left drawn
 *  ahead may no longer be what the next step shows. */
function showPlot(id, plain) {
  return show(id, styled(plain, pageStyle()), EXPLORER_CONFIG).then(scheduleDrawAhead);
}

function draw() {
  const figs = pageFigures(app.frame, app.state);
  return Promise.all(PLOT_IDS.map((id) => showPlot(id, figs[id])));
}

/**
 * The figures the page shows for `state`, whose curves `frame` holds (all four, or
 * those in `ids`): the model's curves with what the person added, the simulated
 * points and path (faded when they are for another state), pinned references, a
 * sweep, the measured points.
 */
function pageFigures(frame, state, ids = PLOT_IDS) {
  const sim = app.sim && { ...app.sim, stale: simStale(state, frame) };
  const out = figures(frame, state, sim, state.lugre ? app.lugre : null, ids);
  if (ids.includes("phase")) out.phase = withSimulatedPath(out.phase, state);
  if (app.sweep) {
    const traces = sweepTraces(app.sweep, state, app.sweep.label);
    for (const id of ["breakaway", "hysteresis"]) {
      if (ids.includes(id)) out[id] = withTraces(out[id], traces[id]);
    }
  }
  if (app.pinned) {
    for (const id of ids) out[id] = withTraces(out[id], app.pinned[id]);
  }
  if (app.measured && ids.includes(app.measured.plot)) {
    out[app.measured.plot] = withTraces(out[app.measured.plot], [{
      type: "scatter", mode: "markers", name: "measured", x: app.measured.x, y: app.measured.y,
      marker: { color: "rgba(90, 90, 90, 0.45)", size: 4 }, hoverinfo: "skip",
    }]);
  }
  return out;
}

function pinCurves() {
  if (!app.frame) return;
  const figs = figures(app.frame, app.state, null, null);
  app.pinned = Object.fromEntries(PLOT_IDS.map((id) => [id, pinnedTraces(figs[id])]));
  $("compare-clear").disabled = false;
  draw();
}

function clearPinned() {
  app.pinned = null;
  $("compare-clear").disabled = true;
  draw();
}

async function runSweep() {
  const name = $("sweep-param").value;
  const spec = paramSpec(name);
  if (!spec || !app.frame) return;
  const values = sweepValues(name, app.state);
  $("sweep-status").textContent = `Sweeping ${spec.label} over ${values.join(", ")}…`;
  try {
    const frames = await Promise.all(values.map((value) => postJSON("/api/explore",
      exploreBody({ ...app.state, [name]: value }))));
    app.sweep = { name, label: spec.label.split(" [")[0], values, frames };
    $("sweep-clear").disabled = false;
    $("sweep-status").textContent = `${values.length} curves of ${spec.label} on the `
      + "break-away plot and the hysteresis loop.";
    await draw();
  } catch (error) {
    $("sweep-status").textContent = `The sweep failed: ${error.message}`;
  }
}

function clearSweep() {
  app.sweep = null;
  $("sweep-clear").disabled = true;
  $("sweep-status").textContent = "";
  draw();
}

function showTourStep(index) {
  app.tour = index;
  const last = index === TOUR.length - 1;
  $("tour-step").textContent = `Step ${index + 1} of ${TOUR.length}: ${TOUR[index].text}`;
  $("tour-next").disabled = last;
  $("tour-start").textContent = "Restart the tour";
  setState(tourState(index, app.presets, app.state));
}

/** The phase figure with the simulated ramp's path (z, ẋ) over the E12 family, faded
 *  when the path is for another state than `state`. */
function withSimulatedPath(figure, state) {
  if (!app.ramp) return figure;
  const trace = simulationPhaseTrace(app.ramp, app.cursor);
  if (app.rampKey !== rampKeyOf(state)) trace.opacity = 0.35;
  return { ...figure, data: [...figure.data, trace] };
}

// ---------------------------------------------------------------------------------
// the ramp experiment at the current k (debounced, abortable): its own plot, the path
// in the phase plot, and the sentence that explains the numbers
// ---------------------------------------------------------------------------------

function rampKeyOf(state = app.state) {
  return JSON.stringify(rampBody(state));
}

function rampBusy() {
  return Boolean(app.rampTimer || app.rampController);
}

function cancelRamp() {
  clearTimeout(app.rampTimer);
  app.rampTimer = null;
  if (app.rampController) app.rampController.abort();
  app.rampController = null;
  if (!rampBusy()) flush("ramp");
}

function scheduleRamp() {
  if (!app.frame) return;
  if (app.ramp && app.rampKey === rampKeyOf()) {
    drawRamp();
    return;
  }
  clearTimeout(app.rampTimer);
  app.rampTimer = setTimeout(runRamp, RAMP_DEBOUNCE_MS);
}

async function runRamp() {
  app.rampTimer = null;
  if (app.rampController) app.rampController.abort();
  const controller = new AbortController();
  app.rampController = controller;
  const key = rampKeyOf();
  try {
    const result = await postJSON("/api/ramp", rampBody(app.state), controller.signal);
    if (controller !== app.rampController) return;
    app.ramp = result;
    app.rampKey = key;
    stopPlay();
    await drawRamp();
    app.rampFrames += 1;
    $("plots").dataset.rampFrame = String(app.rampFrames);
  } catch (error) {
    if (error.name === "AbortError" || controller !== app.rampController) return;
    $("ba-explain").textContent = `The ramp experiment could not be simulated: ${error.message}`;
  }
  if (controller === app.rampController) {
    app.rampController = null;
    if (!rampBusy()) flush("ramp");
  }
}

function drawRamp() {
  if (!app.ramp || !app.frame) return Promise.resolve();
  $("ba-explain").textContent = explainBreakaway(app.ramp, app.state);
  return Promise.all([
    showPlot("ramp", rampFigure(app.ramp, app.state, app.cursor)),
    showPlot("phase", pageFigures(app.frame, app.state, ["phase"]).phase),
  ]);
}

function stopPlay() {
  if (app.playing) cancelAnimationFrame(app.playing);
  app.playing = null;
  app.cursor = null;
  $("ramp-play").setAttribute("aria-pressed", "false");
  $("ramp-play").textContent = "Play";
}

/** Moves a time cursor from 0 to the break-away through the ramp and phase plots. */
function togglePlay() {
  if (app.playing || !app.ramp) {
    stopPlay();
    drawRamp();
    return;
  }
  const end = app.ramp.t_ba ?? app.ramp.t[app.ramp.t.length - 1];
  const started = performance.now();
  $("ramp-play").setAttribute("aria-pressed", "true");
  $("ramp-play").textContent = "Stop";
  const step = (now) => {
    const fraction = Math.min((now - started) / (PLAY_SECONDS * 1000), 1);
    app.cursor = fraction * end;
    drawRamp();
    if (fraction < 1 && app.playing) {
      app.playing = requestAnimationFrame(step);
    } else {
      app.playing = null;
      $("ramp-play").setAttribute("aria-pressed", "false");
      $("ramp-play").textContent = "Play";
    }
  };
  app.playing = requestAnimationFrame(step);
}

function drawBreakaway() {
  if (!app.frame) return Promise.resolve();
  return showPlot("breakaway", pageFigures(app.frame, app.state, ["breakaway"]).breakaway);
}

function showServerError(error) {
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

// ---------------------------------------------------------------------------------
// simulation (debounced, abortable, redraws the break-away plot only)
// ---------------------------------------------------------------------------------

/** The force rates the simulation runs: the phase family's, those of `frame`. */
function simRates(frame = app.frame) {
  return frame ? frame.phase.curves.slice(0, -1).map((curve) => curve.k) : [];
}

function simKey(state = app.state, frame = app.frame) {
  return JSON.stringify(simulateBody(state, simRates(frame)));
}

/** True when the simulated points are for another state than `state`. */
function simStale(state, frame) {
  return app.sim.key !== simKey(state, frame);
}

function cancelSim() {
  clearTimeout(app.simTimer);
  app.simTimer = null;
  if (app.simController) app.simController.abort();
  app.simController = null;
  updateSimBusy();
}

function scheduleSim(now = false) {
  if (!app.frame || (!app.state.sim && !now)
      || (!now && app.sim && !simStale(app.state, app.frame))) {
    updateSimBusy();
    return;
  }
  clearTimeout(app.simTimer);
  app.simTimer = setTimeout(runSim, now ? 0 : SIM_DEBOUNCE_MS);
  updateSimBusy();
}

async function runSim() {
  app.simTimer = null;
  if (app.simController) app.simController.abort();
  const controller = new AbortController();
  app.simController = controller;
  const key = simKey();
  const rates = simRates();
  const status = $("sim-status");
  status.textContent = `Simulating ${rates.length} ramps…`;
  const started = performance.now();
  try {
    const result = await postJSON("/api/simulate", simulateBody(app.state, rates), controller.signal);
    if (controller !== app.simController) return;
    app.sim = { ...result, key };
    const missing = result.u_ba.filter((value) => value === null).length;
    const seconds = ((performance.now() - started) / 1000).toFixed(2);
    status.textContent = `Simulated ${rates.length} ramps in ${seconds} s`
      + (missing ? `; ${missing} did not break away within the step budget` : "");
    await drawBreakaway();
  } catch (error) {
    if (error.name === "AbortError" || controller !== app.simController) return;
    status.textContent = `Simulation failed: ${error.message}`;
  }
  if (controller === app.simController) {
    app.simController = null;
    updateSimBusy();
  }
}

async function ensureLugre() {
  if (!app.state.lugre || app.lugre || app.lugreController || !app.frame) return;
  const controller = new AbortController();
  app.lugreController = controller;
  updateSimBusy();
  try {
    app.lugre = await postJSON("/api/simulate", { model: "lugre", k: simRates() }, controller.signal);
    await drawBreakaway();
  } catch (error) {
    if (error.name !== "AbortError") $("sim-status").textContent = `LuGre failed: ${error.message}`;
  } finally {
    app.lugreController = null;
    updateSimBusy();
  }
}

// ---------------------------------------------------------------------------------
// state changes from the controls, presets, reset and history
// ---------------------------------------------------------------------------------

/** A history entry for the state, only when it is valid: a shared link never opens
 *  broken. Written in a task of its own once the frame is drawn: pushState costs a key
 *  press 1–4 ms (benchmarks/bench_page.py) that the plots should not wait for. */
function commit() {
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

/** `state` with `spec`'s slider at `position` (and Fs/Fc coupled); true when the other
 *  of Fs and Fc moved. */
function moveSlider(state, spec, position) {
  state[spec.name] = sliderToValue(spec, position);
  return couple(state, spec.name);
}

/** Keep Fs ≥ Fc as the person edits one of them in `state`: the other follows
 *  (MODEL.md §1). True when it moved. */
function couple(state, name) {
  const Fc = parseNumber(state.Fc);
  const Fs = parseNumber(state.Fs);
  if (!(Fc > 0 && Fs > 0) || Fs >= Fc) return false;
  if (name === "Fc") state.Fs = Fc;
  else if (name === "Fs") state.Fc = Fs;
  else return false;
  return true;
}

function setState(state, { push = true } = {}) {
  app.state = state;
  writeControls(state);
  if (push) commit();
  refresh();
}

function updatePresetSelect() {
  const name = matchingPreset(app.state, app.presets);
  $("preset").value = name;
  const preset = app.presets.find((p) => p.name === name);
  $("preset-description").textContent = preset ? preset.description : "";
  // the note's s = 1 scaling: say so wherever these numbers are read
  $("units-note").hidden = !(preset ? preset.units === "normalised" : Number(app.state.s) === 1);
}

function wireControls() {
  for (const spec of PARAMS) {
    const box = $(spec.name);
    const range = $(`${spec.name}-range`);
    range.addEventListener("input", () => {
      const coupled = moveSlider(app.state, spec, range.value);
      box.value = String(app.state[spec.name]);
      if (coupled) writeControls(app.state, { except: range });
      refresh();
    });
    range.addEventListener("keydown", (event) => {
      const step = KEY_STEP[event.key];
      app.lastStep = step ? { spec, step } : null;
    });
    range.addEventListener("pointerdown", () => { app.lastStep = null; });
    box.addEventListener("input", () => {
      const value = parseNumber(box.value);
      app.state[spec.name] = Number.isNaN(value) ? box.value : value;
      couple(app.state, spec.name);
      writeControls(app.state, { except: box });
      refresh();
    });
    range.addEventListener("change", commit);
    box.addEventListener("change", commit);
  }
  $("F_hat").addEventListener("change", () => {
    app.state.F_hat = $("F_hat").value;
    commit();
    refresh();
  });
  $("sim").addEventListener("change", () => {
    app.state.sim = $("sim").checked;
    commit();
    scheduleSim();
  });
  $("lugre").addEventListener("change", () => {
    app.state.lugre = $("lugre").checked;
    commit();
    drawBreakaway();
    ensureLugre();
  });
  $("simulate").addEventListener("click", () => scheduleSim(true));
  $("ramp-play").addEventListener("click", togglePlay);
  $("present").addEventListener("change", () => {
    app.state.present = $("present").checked;
    document.body.classList.toggle("present", app.state.present);
    commit();
    draw();
    drawRamp();
  });
  onSchemeChange(() => {
    if (!app.frame) return;
    draw();
    drawRamp();
  });
  $("compare-pin").addEventListener("click", pinCurves);
  $("compare-clear").addEventListener("click", clearPinned);
  $("sweep-run").addEventListener("click", runSweep);
  $("sweep-clear").addEventListener("click", clearSweep);
  $("tour-start").addEventListener("click", () => showTourStep(0));
  $("tour-next").addEventListener("click", () => showTourStep(Math.min(app.tour + 1, TOUR.length - 1)));
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
  for (const button of document.querySelectorAll("[data-export]")) {
    button.addEventListener("click", () => {
      if (button.dataset.export === "csv") exportCsv(button.dataset.plot);
      else exportPng(button.dataset.plot);
    });
  }
  window.addEventListener("popstate", () => {
    app.commitPending = false; // the entry walked to is the state now
    setState(fromQuery(window.location.search, app.defaults), { push: false });
  });
}

function wireTabs() {
  const tabs = [...document.querySelectorAll('[role="tab"]')];
  const select = (tab) => {
    for (const other of tabs) {
      const selected = other === tab;
      other.setAttribute("aria-selected", String(selected));
      other.tabIndex = selected ? 0 : -1;
      $(other.getAttribute("aria-controls")).hidden = !selected;
    }
  };
  for (const [i, tab] of tabs.entries()) {
    tab.addEventListener("click", () => select(tab));
    tab.addEventListener("keydown", (event) => {
      const step = { ArrowRight: 1, ArrowLeft: -1 }[event.key];
      if (!step) return;
      const next = tabs[(i + step + tabs.length) % tabs.length];
      next.focus();
      select(next);
    });
  }
}

/** The data panel's "Use these parameters": fitted values into the state (and the URL),
 *  slider ranges widened to the data's scale, and the measured points overlaid. */
function applyFitted(values, { ranges = {}, measured = null } = {}) {
  if (!app.state || !app.defaults) return false;
  for (const [name, range] of Object.entries(ranges)) {
    const spec = paramSpec(name);
    if (spec) Object.assign(spec, range);
  }
  app.measured = measured;
  setState({ ...app.state, ...values });
  return true;
}

async function init() {
  const response = await getJSON("/api/presets");
  setParams(response.parameters);
  buildControls(document);
  addAheadGraphs(PLOT_IDS);
  wireTabs();
  initDataPanel({ applyParams: applyFitted });
  app.defaults = response.defaults;
  app.presets = response.presets;
  const select = $("preset");
  for (const preset of app.presets) {
    const option = document.createElement("option");
    option.value = preset.name;
    option.textContent = preset.name;
    option.title = preset.description;
    select.append(option);
  }
  for (const spec of PARAMS) {
    const option = document.createElement("option");
    option.value = spec.name;
    option.textContent = spec.label;
    $("sweep-param").append(option);
  }
  $("sweep-param").value = "V";
  app.state = fromQuery(window.location.search, app.defaults);
  document.body.classList.toggle("present", Boolean(app.state.present));
  $("present").checked = Boolean(app.state.present);
  window.history.replaceState(null, "", toQuery(app.state));
  writeControls(app.state);
  wireControls();
  refresh();
}

window.breakaway = {
  /** Resolves once the four plots show the current state (or its inline errors) and
   *  the URL holds it. */
  ready: () => whenIdle("ready", () => app.busy || app.commitPending),
  /** Resolves once no simulation is pending or running. */
  simReady: () => whenIdle("sim", () => app.simBusy),
  /** Resolves once the ramp experiment shows the current state; its answer. */
  rampReady: async () => {
    await whenIdle("ready", () => app.busy);
    await whenIdle("ramp", rampBusy);
    return app.ramp;
  },
  /** A copy of the current state. */
  state: () => JSON.parse(JSON.stringify(app.state)),
  /** Completed redraws, and the last one's duration (input to plots drawn) [ms]. */
  frames: () => app.frames,
  /** Frames that a key press found asked for ahead; `prefetch(false)` stops asking
   *  ahead (the benchmark's alternative). */
  prefetchHits: () => app.prefetchHits,
  prefetch: (on) => { app.prefetchOn = Boolean(on); app.ahead = null; },
  /** `drawAhead(false)`: the frame is asked for ahead but not drawn ahead. */
  drawAhead: (on) => { app.drawAheadOn = Boolean(on); },
  /** Counts per plot: Plotly calls on the shown graphs (`reacts`), plots shown from the
   *  graph drawn ahead (`swaps`), graphs drawn ahead (`drawnAhead`). */
  surfaces: () => ({ ...surfaceStats }),
  /** True once the next arrow step's four plots are drawn (ahead, or already shown). */
  aheadDrawn: () => {
    const figs = aheadFigures();
    return Boolean(figs) && PLOT_IDS.every((id) => holds(id, figs[id]));
  },
  lastRedrawMs: () => app.lastRedrawMs,
  /** Resolves once the data panel runs no fit; the finished fit's report (or null). */
  fitReady,
  fitReport,
};

init().catch((error) => {
  showServerError(error);
  setBusy(false);
  updateSimBusy();
});
