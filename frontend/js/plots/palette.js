// Every colour the figures draw with, grouped by the plot that shows them together.
// Within a group each pair of distinct colours lies at least 40 apart (Euclidean
// distance in sRGB, 0–255) for normal vision and under protan, deutan and tritan
// simulation (Machado, Oliveira & Fernandes 2009, severity 1), in light and in dark
// mode (DARK_INK applied): tests/browser/test_browser_palette.py computes it, here and
// from the traces the page draws. The F̂ curves are Okabe–Ito's colour-blind-safe hues
// (and differ by dash too); the other colours were chosen to keep that distance.

/** Measured points of a fit laid over a model plot: a light, neutral cloud. */
const MEASURED = "#bbbbbb";
/** The current k: its curve in the phase family, its point and line on the break-away curve. */
const CURRENT = "#9467bd";
/** The five curves of a sweep, in the order of the swept values. */
export const SWEEP = ["#920000", "#882255", "#aa7744", "#7a4dff", "#b66dff"];

export const PALETTE = {
  stribeck: { curve: "#0072b2", measured: MEASURED, sweep: SWEEP },
  // the loop's branches by the direction of travel: blue moving +x, orange moving −x
  hysteresis: { forward: "#0072b2", backward: "#e69f00", measured: MEASURED, sweep: SWEEP },
  // z* dotted in the simulation's ink: a grey there came too near the sweep's wine
  phase: { family: "#b8bcc4", current: CURRENT, zStar: "#111111", simulation: "#111111", sweep: SWEEP },
  breakaway: {
    Fc: "#56b4e9", Fs: "#d55e00", avg: "#009e73", self: "#cc79a7", current: CURRENT,
    simulation: "#111111", lugre: "#ff7f00", measured: MEASURED, sweep: SWEEP,
  },
  ramp: { u: "#1f4e99", F: "#e6550d", v: "#555555", e13: "#2ca02c", breakAway: "#111111" },
  // the control loop's three plots (loopplots.js), in the ramp's inks: u, F, the
  // break-away ✕ and the E13 value look the same in both
  loopPosition: { r: "#555555", x: "#1f4e99", breakAway: "#111111" },
  loopError: { e: "#1f4e99", band: "#555555" },
  loopForce: { u: "#1f4e99", F: "#e6550d", stick: "#555555", e13: "#2ca02c", breakAway: "#111111" },
  // the data panel's plots
  fitModel: { measured: "#8a9099", base: "#d62728", final: "#1f4e99" },
  fitResidual: { before: "#c9ccd1", after: "#1f4e99" },
  // the plan's standard errors: now (grey), after the plan (blue), the bar of 100 %
  plan: { now: "#8a9099", after: "#1f4e99", bar: "#111111" },
};

/** Black and dark grey ink (the simulation, reference lines) turned light on a dark
 *  background, where they would vanish. */
export const DARK_INK = { "#111111": "#e4e7eb", "#555555": "#9aa1ab" };
