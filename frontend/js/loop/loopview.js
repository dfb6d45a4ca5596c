// The control loop as a view of the registry (views.js) with a request of its own
// (POST /api/loop): three plots from one answer (loopplots.js), the
// sentence under them (loopexplain.js) and the stick-phase table. The page runs the loop
// itself (loopmodel.js in a worker, 4–5 ms for the default 5-s run; a run over its step
// budget goes to the server), so while its card is on the screen it follows every
// change live, the friction sliders' too (off the screen, a friction slider's run waits
// for the hand to rest: nobody sees it, and a drag of the model plots would share its
// time). Once a state rests, the variants the sentence quotes (Fs = Fc, more Kd,
// compensation switched) are run too, at most four, the previous ones aborted.

import { postJSON } from "../page/api.js";
import { captionOf, paramList, validate } from "../page/controls.js";
import { fmt } from "../page/units.js";
import { buildLoopControls, widenLoopRange } from "./loopcontrols.js";
import { explainLoop, summarise, whatIfStates } from "./loopexplain.js";
import { loopFigures, phaseRows } from "./loopplots.js";
import {
  LOOP_CONTROLS, compScale, fittedLoopState, loadLoopDefaults, localLoop, loopBody, loopDefaults,
  loopSpec, readLoop, writeLoop,
} from "./loopstate.js";
import { onPhone, plotMovedBy, showPlotInView } from "../page/phone.js";
import { onStateLeft } from "../page/render.js";
import { registerStatePart } from "../page/state.js";
import {
  $, app, shownState, whenIdle,
} from "../page/store.js";
import { viewResult, viewsBusy } from "../page/viewrequests.js";
import { registerView } from "../page/views.js";

const LOOP_DEBOUNCE_MS = 30;
/** The variants are asked for once the state has rested this long [ms]. */
const WHATIF_REST_MS = 300;
const KEPT = 8;

const whatifs = { timer: null, controller: null, key: null, cache: new Map() };
const waiting = []; // loopReady()'s, resolved once the sentence is complete

function settled() {
  for (const resolve of waiting.splice(0)) resolve();
}

let onScreen = false; // the loop's card is on the screen (on a phone: in the strip's view)

const FRICTION = captionOf(["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba"], { fHat: true });
const REFERENCE_SIZES = { step: ["h"], ramp: ["w"], sine: ["h", "f"] };

/** The loop's plots are drawn with the friction, the loop's mass and gains, its
 *  reference, compensation and force limit: the caption of their exports. */
function loopCaption(state) {
  const loop = paramList(["Kp", "Ki", "Kd", "m_loop", ...REFERENCE_SIZES[state.ref]], state, { specOf: loopSpec });
  const scale = compScale(state);
  const compensation = scale > 0
    ? `, compensation c = ${fmt(scale)} (${state.comp_model === "fitted" ? "the fitted model" : "the plant's"})` : "";
  const limit = state.limit ? `, ${paramList(["u_max"], state, { specOf: loopSpec })}` : "";
  return `${FRICTION(state)}; a ${state.ref} reference, ${loop}${compensation}${limit}`;
}

/** Asked for live at every change while the card is on the screen; valid states only
 *  (an invalid one is not sent: its errors show at the controls). */
const live = (state) => onScreen && !Object.keys(validate(state)).length;

registerView({
  id: "loop",
  source: "request",
  plots: ["loop-position", "loop-error", "loop-force"],
  caption: loopCaption,
  request: { url: "/api/loop", body: loopBody, debounceMs: LOOP_DEBOUNCE_MS, live, local: localLoop },
  figures: ({ state, result }) => loopFigures(result, state),
  onDraw: (result, state) => showNumbers(result, state),
  onError: (error) => {
    $("loop-explain").textContent = `The control loop could not be simulated: ${error.message}`;
  },
});

function keyOf(state) {
  return JSON.stringify(loopBody(state));
}

/** The sentence and the table for the answer shown; the variants once the state rests. */
function showNumbers(result, state) {
  const key = keyOf(state);
  const current = !viewResult("loop", state)?.stale;
  const cached = current ? whatifs.cache.get(key) : null;
  // an invalid state (a value typed out of range) is drawn from the last valid answer,
  // and its variants are never sent: the server would refuse them
  const valid = !Object.keys(validate(state)).length;
  const wanted = valid && current && Object.keys(whatIfStates(state, result)).length > 0;
  const sentence = $("loop-explain");
  sentence.textContent = explainLoop(result, state, cached ?? null, wanted && !cached);
  sentence.dataset.whatifs = cached || !wanted ? "done" : "pending";
  // read out once the hand rests, not at every live frame
  sentence.setAttribute("aria-busy", String(app.busy));
  // the table under the plots once the hand rests too: rebuilding its rows at every live
  // frame laid the page out anew (a millisecond a frame); meanwhile it is dimmed
  const phases = $("loop-phases");
  phases.dataset.stale = String(app.busy);
  phases.setAttribute("aria-busy", String(app.busy));
  if (!app.busy) fillTable(result, state);
  if (wanted && !cached && !app.busy) askWhatIfs(state, result, key);
  if (!wanted || cached) settled();
}

function fillTable(result, state) {
  const body = $("loop-phases-table").tBodies[0];
  const rows = phaseRows(result).map((row) => {
    const tr = document.createElement("tr");
    for (const value of Object.values(row)) {
      const td = document.createElement("td");
      td.textContent = String(value);
      tr.append(td);
    }
    return tr;
  });
  body.replaceChildren(...rows);
  $("loop-phases-fhat").textContent = state.F_hat;
  $("loop-phases-empty").hidden = rows.length > 0;
}

function cancelWhatIfs() {
  clearTimeout(whatifs.timer);
  whatifs.timer = null;
  whatifs.controller?.abort();
  whatifs.controller = null;
  whatifs.key = null;
}

/** Run the variants of `state` once it has rested, then say what they change. */
function askWhatIfs(state, result, key) {
  if (whatifs.key === key) return;
  cancelWhatIfs();
  whatifs.key = key;
  // the page's state object changes in place as the hand types on: the variants are of
  // the state as it was drawn
  const drawn = { ...state };
  whatifs.timer = setTimeout(async () => {
    whatifs.timer = null;
    if (keyOf(shownState()) !== key) {
      // the page moved on while the timer waited (on a loaded machine, past an edit)
      whatifs.key = null;
      return;
    }
    const controller = new AbortController();
    whatifs.controller = controller;
    const variants = whatIfStates(drawn, result);
    try {
      const run = async (body) => (await localLoop(body))
        ?? postJSON("/api/loop", body, controller.signal);
      const runs = await Promise.all(Object.entries(variants).map(async ([name, variant]) => [
        name, summarise(await run(loopBody(variant)))]));
      const summary = Object.fromEntries(runs);
      if (variants.kd) summary.kdValue = variants.kd.Kd;
      whatifs.cache.set(key, summary);
      if (whatifs.cache.size > KEPT) whatifs.cache.delete(whatifs.cache.keys().next().value);
      whatifs.controller = null;
      whatifs.key = null;
      const state = shownState();
      if (keyOf(state) === key && app.results.loop) showNumbers(app.results.loop.value, state);
    } catch (error) {
      if (error.name === "AbortError") return;
      whatifs.controller = null;
      whatifs.key = null;
      $("loop-explain").dataset.whatifs = "failed";
      settled();
    }
  }, WHATIF_REST_MS);
}

onStateLeft(cancelWhatIfs);

/** True while the sentence waits for its variants. */
export function loopBusy() {
  return $("loop-explain").dataset.whatifs === "pending";
}

/** Resolves once the loop's plots, sentence and table show the current state (its
 *  variants run); the answer shown. */
export async function loopReady() {
  await whenIdle("ready", () => app.busy);
  await whenIdle("views", viewsBusy);
  if (loopBusy()) await new Promise((resolve) => { waiting.push(resolve); });
  return app.results.loop?.value;
}

/** Bring the loop's card into view (on a phone: into the strip at the top, which is
 *  always in view, so the page stays where it is). */
export function openLoopView() {
  if (onPhone()) showPlotInView("loop");
  else $("card-loop").scrollIntoView({ block: "start", behavior: "instant" });
  $("card-loop-title").focus({ preventScroll: true });
}

/** On a phone, the plot of the loop in view (the others stay laid out under it). */
function showLoopPlot(id) {
  document.querySelector(".loop-plots").dataset.inView = id;
  $("card-loop").dataset.inView = id;
  for (const button of document.querySelectorAll("[data-loop-show]")) {
    button.setAttribute("aria-pressed", String(button.dataset.loopShow === id));
  }
}

/** The loop's defaults from the server, its state part and its controls; before the
 *  page reads its state from the URL. */
export async function initLoop() {
  await loadLoopDefaults(postJSON);
  registerStatePart({ name: "loop", defaults: loopDefaults, read: readLoop, write: writeLoop });
  buildLoopControls();
  // on a phone the loop's card comes into view with any of its controls, and follows
  // the friction's (the other plots a friction slider moves stay in view)
  plotMovedBy("loop", ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "F_hat"]);
  plotMovedBy("loop", [...LOOP_CONTROLS.map((spec) => spec.name), "loop-ref", "loop-comp",
    "loop-comp-model", "loop-limit", "loop-show"]);
  for (const button of document.querySelectorAll("[data-loop-show]")) {
    button.addEventListener("click", () => showLoopPlot(button.dataset.loopShow));
  }
  new IntersectionObserver(([entry]) => { onScreen = entry.isIntersecting; }).observe($("card-loop"));
  $("loop-show").addEventListener("click", openLoopView);
}

/** The part of a state that tries fitted `values` in the loop (loopstate.js), with the
 *  loop's sliders widened to its scale. */
export function fittedLoop(values, compensatorOnly) {
  const part = fittedLoopState(values, app.state, app.defaults, compensatorOnly);
  for (const [name, value] of Object.entries(part)) widenLoopRange(name, value);
  return part;
}
