// The ramp simulated at the phase family's rates (E7) and LuGre's break-away beside it:
// the points of the break-away plot. Debounced and abortable, run once a frame is drawn
// and only redrawing the break-away plot, so they never hold up a slider.

import { postJSON } from "../page/api.js";
import { onFrameDrawn, onStateLeft, redraw } from "../page/render.js";
import {
  $, app, commit, setToggle, shownState, updateSimBusy,
} from "../page/store.js";
import { simulateBody } from "../page/state.js";

const SIM_DEBOUNCE_MS = 350;

/** The force rates the simulation runs: the phase family's, those of `frame`. */
function simRates(frame = app.frame) {
  return frame ? frame.phase.curves.slice(0, -1).map((curve) => curve.k) : [];
}

function simKey(state = shownState(), frame = app.frame) {
  return JSON.stringify(simulateBody(state, simRates(frame)));
}

/** True when the simulated points are for another state than `state`. */
export function simStale(state, frame) {
  return app.sim.key !== simKey(state, frame);
}

export function cancelSim() {
  clearTimeout(app.simTimer);
  app.simTimer = null;
  if (app.simController) app.simController.abort();
  app.simController = null;
  updateSimBusy();
}

/** Simulate the current state after the debounce (at once when `now`), unless the
 *  points shown are for it already or the automatic simulation is off. */
export function scheduleSim(now = false) {
  if (!app.frame || (!app.state.sim && !now)
      || (!now && app.sim && !simStale(shownState(), app.frame))) {
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
    const result = await postJSON("/api/simulate", simulateBody(shownState(), rates), controller.signal);
    if (controller !== app.simController) return;
    app.sim = { ...result, key };
    const missing = result.u_ba.filter((value) => value === null).length;
    const seconds = ((performance.now() - started) / 1000).toFixed(2);
    status.textContent = `Simulated ${rates.length} ramps in ${seconds} s`
      + (missing ? `; ${missing} did not break away within the step budget` : "");
    await redraw(["breakaway"]);
  } catch (error) {
    if (error.name === "AbortError" || controller !== app.simController) return;
    status.textContent = `Simulation failed: ${error.message}`;
  }
  if (controller === app.simController) {
    app.simController = null;
    updateSimBusy();
  }
}

/** LuGre's points, with the 1995 parameters: asked for once, when first shown. */
export async function ensureLugre() {
  if (!app.state.lugre || app.lugre || app.lugreController || !app.frame) return;
  const controller = new AbortController();
  app.lugreController = controller;
  updateSimBusy();
  try {
    app.lugre = await postJSON("/api/simulate", { model: "lugre", k: simRates() }, controller.signal);
    await redraw(["breakaway"]);
  } catch (error) {
    if (error.name !== "AbortError") $("sim-status").textContent = `LuGre failed: ${error.message}`;
  } finally {
    app.lugreController = null;
    updateSimBusy();
  }
}

// the pending simulation is for the state just left: dropped, so it does not compete
// with the new frame, and scheduled again once that is drawn
onStateLeft(cancelSim);
onFrameDrawn(() => {
  scheduleSim();
  ensureLugre();
});

/** Wire the simulation's own controls. */
export function wireSimulation() {
  $("sim").addEventListener("change", () => {
    setToggle("sim", $("sim").checked);
    commit();
    scheduleSim();
  });
  $("lugre").addEventListener("change", () => {
    setToggle("lugre", $("lugre").checked);
    commit();
    redraw(["breakaway"]);
    ensureLugre();
  });
  $("simulate").addEventListener("click", () => scheduleSim(true));
}
