// The ramp experiment at the current k as a view with its own request (POST /api/ramp),
// computed in the page when the run is short (rampmodel.js, the server's integrator):
// its plot, the simulated path over the phase family, the sentence that explains the
// numbers, and Play, which moves a time cursor through both plots.

import { captionOf } from "../page/controls.js";
import {
  explainBreakaway, rampBody, rampFigure, simulationPhaseTrace,
} from "./ramp.js";
import { rampExperiment } from "../models/rampmodel.js";
import { $, app, setAttr, setText } from "../page/store.js";
import { drawView, viewResult } from "../page/viewrequests.js";
import { registerOverlay, registerView } from "../page/views.js";

const RAMP_DEBOUNCE_MS = 60;
const PLAY_SECONDS = 4;

registerView({
  id: "ramp",
  source: "request",
  caption: captionOf(["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "k", "m"], { fHat: true }),
  request: { url: "/api/ramp", body: rampBody, debounceMs: RAMP_DEBOUNCE_MS, local: rampExperiment },
  redraws: ["phase"],
  figure: ({ state, result }) => rampFigure(result, state, app.cursor),
  onResult: stopPlay,
  onDraw: (result, state) => {
    setText($("ba-explain"), explainBreakaway(result, state));
  },
  onError: (error) => {
    $("ba-explain").textContent = `The ramp experiment could not be simulated: ${error.message}`;
  },
});

/** The phase figure with the simulated ramp's path (z, ẋ) over the E12 family, faded
 *  when the path is for another state. */
registerOverlay((figures, { state }) => {
  const ramp = figures.phase && viewResult("ramp", state);
  if (!ramp) return;
  const trace = simulationPhaseTrace(ramp.value, state, app.cursor);
  if (ramp.stale) trace.opacity = 0.35;
  figures.phase = { ...figures.phase, data: [...figures.phase.data, trace] };
});

/** Play stopped (each new answer stops it): the button's words and state written only
 *  when they change, as each answer of a drag of m would lay the page out anew. */
function stopPlay() {
  if (app.playing) cancelAnimationFrame(app.playing);
  app.playing = null;
  app.cursor = null;
  setAttr($("ramp-play"), "aria-pressed", "false");
  setText($("ramp-play"), "Play");
}

/** Moves a time cursor from 0 to the break-away through the ramp and phase plots. */
function togglePlay() {
  const ramp = app.results.ramp?.value;
  if (app.playing || !ramp) {
    stopPlay();
    drawView("ramp");
    return;
  }
  const end = ramp.t_ba ?? ramp.t[ramp.t.length - 1];
  const started = performance.now();
  $("ramp-play").setAttribute("aria-pressed", "true");
  $("ramp-play").textContent = "Stop";
  const step = (now) => {
    const fraction = Math.min((now - started) / (PLAY_SECONDS * 1000), 1);
    app.cursor = fraction * end;
    drawView("ramp");
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

export function wireRamp() {
  $("ramp-play").addEventListener("click", togglePlay);
}
