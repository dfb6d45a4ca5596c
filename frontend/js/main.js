// The explorer page: start-up, the link to the data panel, and the hooks for
// tests and scripts (window.breakaway). The page's modules, grouped by what they serve:
//   page/       the state and its signals (store.js, state.js), the one render path
//               (render.js) over the registry of views (views.js, viewrequests.js), the
//               controls (controls.js, inputs.js), the plot in view on a phone (phone.js)
//               and the requests to the server (api.js)
//   models/     the model computed in the page: the curves (model.js), the integrator
//               and the ramp's and the loop's dynamic models (loopworker.js runs the
//               loop off the main thread)
//   plots/      the four model plots (plots.js, modelviews.js), the colours, the live
//               drawing while a hand moves (livedraw.js, axes.js) and Plotly's
//               (surfaces.js, draw.js), and the exports
//   ramp/       the ramp experiment and the simulated break-away points
//   loop/       the control loop: its state, controls, plots and sentence
//   datapanel/  measured data: the fit, its tables and figures, the quiz, the outputs
//   teaching/   the first minute's introduction, pin, sweep and the guided tour
//
// For tests and scripts: #plots carries data-ready="true|false" and data-frame=<count>;
// window.breakaway.ready() resolves once the plots show the current state (or its
// inline errors), window.breakaway.simReady() once the simulation points are settled.

import { getJSON } from "./page/api.js";
import {
  PARAMS, buildControls, controlLabel, paramList, paramSpec, setParams, writeControls,
} from "./page/controls.js";
import { initDataPanel } from "./datapanel/datapanel.js";
import { fitReady, fitReport } from "./datapanel/panelstate.js";
import { explorerParams, measuredOverlay } from "./datapanel/fitparams.js";
import { setState, wireControls } from "./page/inputs.js";
import { wireIntro } from "./teaching/intro.js";
import { wireLessons } from "./teaching/lessons.js";
import { loopSpec } from "./loop/loopstate.js";
import {
  fittedLoop, initLoop, loopReady, openLoopView,
} from "./loop/loopview.js";
import "./plots/modelviews.js";
import { initPhone } from "./page/phone.js";
import { wireRamp } from "./ramp/rampview.js";
import { SETTLE_MS, refresh, showServerError } from "./page/render.js";
import { wireSimulation } from "./ramp/simulation.js";
import { fromQuery, toQuery } from "./page/state.js";
import {
  $, app, setBusy, updateSimBusy, whenIdle,
} from "./page/store.js";
import { surfaceStats } from "./plots/surfaces.js";
import { withTraces } from "./teaching/teach.js";
import { viewsBusy } from "./page/viewrequests.js";
import { registerOverlay } from "./page/views.js";

/** The measured points of a fit, on the plot that matches the data's kind. */
registerOverlay((figures) => {
  const { measured } = app;
  if (!measured || !figures[measured.plot]) return;
  figures[measured.plot] = withTraces(figures[measured.plot], [{
    type: "scatter", mode: "markers", name: "measured", x: measured.x, y: measured.y,
    marker: { color: "rgba(90, 90, 90, 0.45)", size: 4 }, hoverinfo: "skip",
  }]);
});

/** The data panel's "Use these parameters": fitted values into the state (and the URL),
 *  in the data's units, slider ranges widened to the data's scale, and the measured
 *  points overlaid; the state set, or false before the explorer is ready. */
function applyFitted(values, { ranges = {}, measured = null, units = null } = {}) {
  if (!app.state || !app.defaults) return false;
  for (const [name, range] of Object.entries(ranges)) {
    const spec = paramSpec(name);
    if (spec) Object.assign(spec, range);
  }
  app.measured = measured;
  setState({ ...app.state, ...values, units: units ?? app.state.units });
  return app.state;
}

/** The data panel's "Try this model in a control loop": the fitted model in the plant
 *  (the loop carried to its scale), or only in the compensator; the loop in view. */
function tryFittedInLoop(job, { compensatorOnly }) {
  if (!app.state || !app.defaults) return false;
  const { values, notes, ranges, units } = explorerParams(job.report);
  const loop = fittedLoop(values, compensatorOnly);
  const state = compensatorOnly
    ? applyFitted(loop, { measured: app.measured, units })
    : applyFitted({ ...values, ...loop }, { ranges, measured: measuredOverlay(job), units });
  if (!state) return false;
  openLoopView();
  const specOf = (name) => paramSpec(name) ?? loopSpec(name);
  const list = (part) => paramList(Object.keys(part).filter((name) => typeof part[name] === "number"),
    state, { values: part, specOf });
  return compensatorOnly
    ? `The compensator takes the fitted model (${list(values)}); the plant keeps the sliders.`
    : `The plant takes the fitted model (${list(values)}) and the loop its scale: ${list(loop)}.`
      + `${notes.length ? ` Note: ${notes.join("; ")}.` : ""}`;
}

function fillMenus() {
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
    option.dataset.labelOf = spec.name;
    option.textContent = controlLabel(spec, null);
    $("sweep-param").append(option);
  }
  $("sweep-param").value = "V";
}

async function init() {
  const [response] = await Promise.all([getJSON("/api/presets"), initLoop()]);
  setParams(response.parameters);
  buildControls(document);
  initPhone();
  initDataPanel({
    applyParams: applyFitted, tryInLoop: tryFittedInLoop, explorerS: () => app.state?.s,
  });
  app.defaults = response.defaults;
  app.presets = response.presets;
  fillMenus();
  app.state = fromQuery(window.location.search, app.defaults);
  $("present").checked = Boolean(app.state.present);
  window.history.replaceState(null, "", toQuery(app.state));
  writeControls(app.state);
  wireControls();
  wireSimulation();
  wireRamp();
  wireLessons(setState);
  wireIntro();
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
    await whenIdle("views", viewsBusy);
    return app.results.ramp?.value;
  },
  /** Resolves once the control loop shows the current state, its sentence complete
   *  (the variants it quotes run); its answer. */
  loopReady,
  /** The plant's parameters and the gains of the loop's answer shown, or null. */
  loopParams: () => {
    const shown = app.results.loop?.value;
    return shown ? { ...shown.params, ...shown.controller } : null;
  },
  /** A copy of the current state. */
  state: () => JSON.parse(JSON.stringify(app.state)),
  /** States shown so far (live or settled), and the last settle's duration [ms]. */
  frames: () => app.frames,
  /** `live(false)`: no live frames; every change is drawn by Plotly.react as it comes
   *  (the benchmark's alternative). */
  live: (on) => { app.liveOn = Boolean(on); },
  /** How long a hand must rest before the settled drawing [ms]. */
  settleMs: SETTLE_MS,
  /** Counts: Plotly.react calls (`reacts`), plots drawn live on their canvas (`live`),
   *  of those copied from a frame painted ahead (`ahead`), frames painted ahead
   *  (`painted`). */
  surfaces: () => ({ ...surfaceStats }),
  /** The parameters of the answer view `id` (the ramp) shows, or null. */
  viewParams: (id) => app.results[id]?.value?.params ?? null,
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
