// The four model plots as views of the registry (views.js), drawn from each
// /api/explore frame by the builders of plots.js, their exports captioned with the
// parameters each is drawn with; under the break-away plot, the sentence on its shaded
// band of rates (models/sensitivity.js), once a state settles.

import { bandKey, rateBand } from "../models/sensitivity.js";
import { captionOf } from "../page/controls.js";
import { onComputeAhead, onFrameDrawn } from "../page/render.js";
import { exploreBody } from "../page/state.js";
import { $, app } from "../page/store.js";
import { fmt, quantity } from "../page/units.js";
import { registerView } from "../page/views.js";
import { simStale } from "../ramp/simulation.js";
import {
  breakawayFigure, hysteresisFigure, phaseFigure, stribeckFigure,
} from "./plots.js";

const STRIBECK = ["Fc", "Fs", "V", "delta", "sigma"];
const QUASI_STATIC = [...STRIBECK, "s", "k", "z_ba"];

/** Bands kept: the current state's and those one key press away (made ahead). */
const BANDS_KEPT = 4;
const bands = new Map();

/** The band of the state's parameters, computed once per set of those it depends on
 *  (1201 rates, four break-away forces each: a tenth of a live frame under a phone's
 *  processor; a drag of k, which the band does not depend on, computed it each frame). */
function bandOf(state) {
  const body = exploreBody(state);
  const key = bandKey(body);
  if (!bands.has(key)) {
    bands.set(key, rateBand(body, body.F_hat));
    if (bands.size > BANDS_KEPT) bands.delete(bands.keys().next().value);
  }
  return bands.get(key);
}

onComputeAhead(bandOf);

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
    app.sim && { ...app.sim, stale: simStale(state, frame) }, state.lugre ? app.lugre : null,
    bandOf(state)),
});

/** The sentence under the break-away plot that says what the band is and why, in the
 *  units of `state`. */
function bandSentence(band, state) {
  if (!band) {
    return "Fs = Fc: there is no Stribeck drop, so F_ba(k) does not depend on V or δ "
      + "at any rate; every ramp measures the same level.";
  }
  const { F_hat: fHat, V } = exploreBody(state);
  return `Shaded: the rates k = ${fmt(band.k[0])} to ${quantity(band.k[1], "N/s", state)} where F_ba(k) `
    + `changes most with V and δ (F̂ = ${fHat}). There the break-away speed `
    + `ẋ* = k/(s·F̂·|ln z*|), ${fmt(band.speed[0])} to ${quantity(band.speed[1], "m/s", state)}, falls inside `
    + `the Stribeck drop around V = ${quantity(V, "m/s", state)}; slower ramps break away at about Fs, `
    + "faster ones at about Fc, and measure those levels and nothing of V or δ.";
}

onFrameDrawn(() => {
  $("ba-band").textContent = bandSentence(bandOf(app.state), app.state);
});
