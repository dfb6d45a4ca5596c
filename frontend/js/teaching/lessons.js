// The teaching tools on the page: pinned reference curves, a parameter sweep and the
// guided tour. Their state lives in `app`; the traces come from teach.js's pure
// functions, laid over the model plots as overlays of the view registry.

import { postJSON } from "../page/api.js";
import { controlLabel, paramSpec } from "../page/controls.js";
import { PLOT_IDS, figures } from "../plots/plots.js";
import { onPhone, showPlotInView } from "../page/phone.js";
import { redraw } from "../page/render.js";
import { exploreBody, partDefaults } from "../page/state.js";
import {
  $, app, shownState, whenIdle,
} from "../page/store.js";
import {
  TOUR, TOUR_DOCS, pinnedTraces, sweepTraces, sweepValues, sweptPlots, tourState, withTraces,
} from "./teach.js";
import { registerOverlay } from "../page/views.js";

/** What each plot calls itself in a sentence. */
const PLOT_NAMES = {
  stribeck: "the Stribeck curve", hysteresis: "the hysteresis loop",
  phase: "the phase curve of the current k", breakaway: "the break-away curve",
};

registerOverlay((figs, { state }) => {
  if (!app.sweep) return;
  const traces = sweepTraces(app.sweep, state, app.sweep.label);
  for (const [id, swept] of Object.entries(traces)) {
    if (!figs[id]) continue;
    const figure = withTraces(figs[id], swept);
    // the swept values named in a legend below the plot, where it covers no curve
    figs[id] = { ...figure, layout: { ...figure.layout, showlegend: true,
      legend: { orientation: "h", x: 0, y: -0.2, yanchor: "top" },
      margin: { ...figure.layout.margin, b: 80 } } };
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
  const figs = figures(app.frame, shownState(), null, null);
  app.pinned = Object.fromEntries(PLOT_IDS.map((id) => [id, pinnedTraces(figs[id])]));
  $("compare-clear").disabled = false;
  redraw();
}

function clearPinned() {
  app.pinned = null;
  $("compare-clear").disabled = true;
  redraw();
}

function names(list) {
  return list.length > 1 ? `${list.slice(0, -1).join(", ")} and ${list[list.length - 1]}` : list[0];
}

/** Sweep parameter `name` around the state shown once it is settled (its frame is
 *  the reference the swept curves must differ from). */
let sweeps = 0; // each sweep asked for or cleared; an older one's answer is dropped

async function runSweep(name = $("sweep-param").value) {
  sweeps += 1;
  const asked = sweeps;
  await whenIdle("ready", () => app.busy);
  const spec = paramSpec(name);
  if (!spec || !app.frame || asked !== sweeps) return;
  $("sweep-param").value = name;
  const state = shownState();
  const values = sweepValues(name, state);
  const named = controlLabel(spec, state);
  $("sweep-status").textContent = `Sweeping ${named} over ${values.join(", ")}…`;
  try {
    const frames = await Promise.all(values.map((value) => postJSON("/api/explore",
      exploreBody({ ...state, [name]: value }))));
    if (asked !== sweeps) return;
    const sweep = { name, label: spec.named, values, frames };
    sweep.plots = sweptPlots(sweep, state, app.frame);
    app.sweep = sweep;
    $("sweep-clear").disabled = false;
    const unmoved = Object.keys(PLOT_NAMES).filter((id) => !sweep.plots.includes(id));
    $("sweep-status").textContent = sweep.plots.length
      ? `${values.length} curves of ${named} on ${names(sweep.plots.map((id) => PLOT_NAMES[id]))}`
        + `${unmoved.length ? `; ${sweep.label} leaves ${names(unmoved.map((id) => PLOT_NAMES[id]))} `
          + `as ${unmoved.length > 1 ? "they are" : "it is"}` : ""}.`
      : `${named} changes none of the model's curves (only the simulation).`;
    await redraw();
  } catch (error) {
    $("sweep-status").textContent = `The sweep failed: ${error.message}`;
  }
}

function clearSweep() {
  sweeps += 1;
  app.sweep = null;
  $("sweep-clear").disabled = true;
  $("sweep-status").textContent = "";
  redraw();
}

/** Bring the card of plot `id` into view: on a phone into the strip at the top; else the
 *  page scrolls to it when it is not all on the screen (the tour's text stays in view
 *  in the controls beside it). */
function showCard(id) {
  if (onPhone()) {
    showPlotInView(id);
    return;
  }
  const card = $(`card-${id}`);
  const box = card.getBoundingClientRect();
  if (box.top >= 0 && box.bottom <= window.innerHeight) return;
  const still = window.matchMedia("(prefers-reduced-motion: reduce)").matches;
  card.scrollIntoView({ block: box.height <= window.innerHeight ? "nearest" : "start",
    behavior: still ? "instant" : "smooth" });
}

/** Wire the tools; `setState(state)` moves the explorer (the tour's steps). */
export function wireLessons(setState) {
  // each step sets its state, brings its plot into view (on a phone) and sweeps the
  // parameter it is about, so that the plots change, not only the text
  const showTourStep = (index) => {
    app.tour = index;
    const step = TOUR[index];
    const state = tourState(index, app.presets, app.state, partDefaults);
    $("tour-step").textContent = `Step ${index + 1} of ${TOUR.length}: ${step.text(state)}`;
    const doc = TOUR_DOCS[step.plot];
    const link = $("tour-doc").querySelector("a");
    link.href = `/guide/${doc.href}`;
    link.textContent = `More in the documentation: ${doc.title}`;
    $("tour-doc").hidden = false;
    $("tour-next").disabled = index === TOUR.length - 1;
    $("tour-start").textContent = "Restart the tour";
    setState(state);
    showCard(step.plot);
    if (step.sweep) runSweep(step.sweep);
    else if (app.sweep) clearSweep();
  };
  $("compare-pin").addEventListener("click", pinCurves);
  $("compare-clear").addEventListener("click", clearPinned);
  $("sweep-run").addEventListener("click", () => runSweep());
  $("sweep-clear").addEventListener("click", clearSweep);
  $("tour-start").addEventListener("click", () => showTourStep(0));
  $("tour-next").addEventListener("click", () => showTourStep(Math.min(app.tour + 1, TOUR.length - 1)));
}
