// The four model plots as views of the registry (views.js), drawn from each
// /api/explore frame by the builders of plots.js; their exports captioned with the
// parameters each is drawn with.

import { captionOf } from "../page/controls.js";
import { app } from "../page/store.js";
import { registerView } from "../page/views.js";
import { simStale } from "../ramp/simulation.js";
import {
  breakawayFigure, hysteresisFigure, phaseFigure, stribeckFigure,
} from "./plots.js";

const STRIBECK = ["Fc", "Fs", "V", "delta", "sigma"];
const QUASI_STATIC = [...STRIBECK, "s", "k", "z_ba"];

registerView({
  id: "stribeck", source: "frame", caption: captionOf(STRIBECK),
  figure: ({ frame, state }) => stribeckFigure(frame, state),
});
registerView({
  id: "hysteresis", source: "frame", caption: captionOf([...STRIBECK, "s"]),
  figure: ({ frame, state }) => hysteresisFigure(frame, state),
});
registerView({
  id: "phase", source: "frame", caption: captionOf(QUASI_STATIC, { fHat: true }),
  figure: ({ frame, state }) => phaseFigure(frame, state),
});
registerView({
  id: "breakaway", source: "frame",
  // the simulated points are the ramp's, with the mass m
  caption: (state) => captionOf(state.sim ? [...QUASI_STATIC, "m"] : QUASI_STATIC, { fHat: true })(state),
  // the simulated points are drawn faded while they are for another state
  figure: ({ frame, state }) => breakawayFigure(frame, state,
    app.sim && { ...app.sim, stale: simStale(state, frame) }, state.lugre ? app.lugre : null),
});
