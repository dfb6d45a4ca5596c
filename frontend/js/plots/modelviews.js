// The four model plots as views of the registry (views.js), drawn from each
// /api/explore frame by the builders of plots.js.

import { AXES, breakawayFigure, hysteresisFigure, phaseFigure, stribeckFigure } from "./plots.js";
import { simStale } from "../ramp/simulation.js";
import { app } from "../page/store.js";
import { registerView } from "../page/views.js";

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
    app.sim && { ...app.sim, stale: simStale(state, frame) }, state.lugre ? app.lugre : null),
});

