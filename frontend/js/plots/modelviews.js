// The four model plots as views of the registry (views.js), drawn from each
// /api/explore frame by the builders of plots.js; under the break-away plot, the
// sentence on its shaded band of rates (models/sensitivity.js), once a state settles.

import { AXES, breakawayFigure, hysteresisFigure, phaseFigure, stribeckFigure } from "./plots.js";
import { bandSentence, rateBand } from "../models/sensitivity.js";
import { simStale } from "../ramp/simulation.js";
import { onFrameDrawn } from "../page/render.js";
import { exploreBody } from "../page/state.js";
import { $, app } from "../page/store.js";
import { registerView } from "../page/views.js";

const bands = { key: null, band: null };

/** The band of the state's parameters, computed once per set of them. */
function bandOf(state) {
  const body = exploreBody(state);
  const key = JSON.stringify(body);
  if (bands.key !== key) {
    bands.key = key;
    bands.band = rateBand(body, body.F_hat);
  }
  return bands.band;
}

registerView({
  id: "stribeck", source: "frame", axes: AXES.stribeck,
  figure: ({ frame }) => stribeckFigure(frame),
});
registerView({
  id: "hysteresis", source: "frame", axes: AXES.hysteresis,
  figure: ({ frame, state }) => hysteresisFigure(frame, state),
});
registerView({
  id: "phase", source: "frame", axes: AXES.phase,
  figure: ({ frame, state }) => phaseFigure(frame, state),
});
registerView({
  id: "breakaway", source: "frame", axes: AXES.breakaway,
  // the simulated points are drawn faded while they are for another state
  figure: ({ frame, state }) => breakawayFigure(frame, state,
    app.sim && { ...app.sim, stale: simStale(state, frame) }, state.lugre ? app.lugre : null,
    bandOf(state)),
});

onFrameDrawn(() => {
  const body = exploreBody(app.state);
  $("ba-band").textContent = bandSentence(bandOf(app.state), body, body.F_hat);
});

