// The teaching tools on the page: pinned reference curves, a parameter sweep and the
// guided tour. Their state lives in `app`; the traces come from teach.js's pure
// functions, laid over the model plots as overlays of the view registry.

import { postJSON } from "./api.js";
import { paramSpec } from "./controls.js";
import { PLOT_IDS, figures } from "./plots.js";
import { redraw } from "./render.js";
import { exploreBody } from "./state.js";
import { $, app } from "./store.js";
import {
  TOUR, pinnedTraces, sweepTraces, sweepValues, tourState, withTraces,
} from "./teach.js";
import { registerOverlay } from "./views.js";

registerOverlay((figs, { state }) => {
  if (!app.sweep) return;
  const traces = sweepTraces(app.sweep, state, app.sweep.label);
  for (const id of ["breakaway", "hysteresis"]) {
    if (figs[id]) figs[id] = withTraces(figs[id], traces[id]);
  }
});

registerOverlay((figs) => {
  if (!app.pinned) return;
  for (const id of Object.keys(figs)) {
    if (app.pinned[id]) figs[id] = withTraces(figs[id], app.pinned[id]);
  }
});

function pinCurves() {
  if (!app.frame) return;
  const figs = figures(app.frame, app.state, null, null);
  app.pinned = Object.fromEntries(PLOT_IDS.map((id) => [id, pinnedTraces(figs[id])]));
  $("compare-clear").disabled = false;
  redraw();
}

function clearPinned() {
  app.pinned = null;
  $("compare-clear").disabled = true;
  redraw();
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
    await redraw();
  } catch (error) {
    $("sweep-status").textContent = `The sweep failed: ${error.message}`;
  }
}

function clearSweep() {
  app.sweep = null;
  $("sweep-clear").disabled = true;
  $("sweep-status").textContent = "";
  redraw();
}

/** Wire the tools; `setState(state)` moves the explorer (the tour's steps). */
export function wireLessons(setState) {
  const showTourStep = (index) => {
    app.tour = index;
    const last = index === TOUR.length - 1;
    $("tour-step").textContent = `Step ${index + 1} of ${TOUR.length}: ${TOUR[index].text}`;
    $("tour-next").disabled = last;
    $("tour-start").textContent = "Restart the tour";
    setState(tourState(index, app.presets, app.state));
  };
  $("compare-pin").addEventListener("click", pinCurves);
  $("compare-clear").addEventListener("click", clearPinned);
  $("sweep-run").addEventListener("click", runSweep);
  $("sweep-clear").addEventListener("click", clearSweep);
  $("tour-start").addEventListener("click", () => showTourStep(0));
  $("tour-next").addEventListener("click", () => showTourStep(Math.min(app.tour + 1, TOUR.length - 1)));
}
