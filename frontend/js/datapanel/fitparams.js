// What a finished fit gives the explorer, as pure functions: the parameter values of
// "Use these parameters" (with the slider ranges widened to the data's scale), the
// measured points to overlay on the matching plot, and the message of a bad file.

import { ApiError } from "../page/api.js";
import { PARAMS, roundSignificant } from "../page/controls.js";
import { unitsOfReport } from "../page/units.js";

/** Explorer parameters that "Use these parameters" sets (rounded to this many digits). */
const DIGITS = 6;

/**
 * The explorer values a report gives, the units of its data (units.js), and notes for
 * the person: Fc, Fs, V, δ from the
 * final model (for asymmetric data these are the positive-direction levels), s when the
 * data determine it, σ when the viscous effect was found (else 0). Values are rounded to
 * DIGITS significant digits; a value beyond its slider's range is kept (the number box
 * holds any value; the slider rests at its end) and named in the notes.
 */
export function explorerParams(report, specs = PARAMS) {
  const fitted = report.final.params;
  const values = {};
  for (const name of ["Fc", "Fs", "V", "delta"]) {
    if (Number.isFinite(fitted[name])) values[name] = roundSignificant(fitted[name], DIGITS);
  }
  const notes = [];
  if (report.kind === "timeseries" && Number.isFinite(fitted.s)) {
    values.s = roundSignificant(fitted.s, DIGITS);
  } else if (report.kind === "breakaway") {
    notes.push("s is kept: a break-away fit takes it from the file (it assumes F̂ = avg, z* = 0.95)");
  } else {
    notes.push("s is kept: steady data do not determine it");
  }
  values.sigma = report.effects.includes("viscous") && Number.isFinite(fitted.sigma)
    ? roundSignificant(fitted.sigma, DIGITS) : 0;
  if (report.effects.includes("viscous-power")) {
    // the explorer's σ is the linear σ·v of E2; a curve σ·|v|ⁿ has no slider
    notes.push(`the fitted curve σ·|v|^n (σ = ${roundSignificant(fitted.sigma, DIGITS)}, ` +
      `n = ${roundSignificant(fitted.n, DIGITS)}) has no slider here: σ stays 0`);
  }
  if (values.Fs < values.Fc) values.Fs = values.Fc; // rounding never does this; be safe
  // sliders reach the data's scale (kN for a damper): a range is widened by decades
  const ranges = {};
  const widened = [];
  for (const [name, value] of Object.entries(values)) {
    const spec = specs.find((s) => s.name === name);
    if (!spec || spec.scale === "linear" || !(value > 0)) continue;
    const min = value < spec.min ? 10 ** Math.floor(Math.log10(value / 10)) : spec.min;
    const max = value > spec.max ? 10 ** Math.ceil(Math.log10(value * 10)) : spec.max;
    if (min !== spec.min || max !== spec.max) {
      ranges[name] = { min, max };
      const low = spec.scale === "log0" ? 0 : min;
      widened.push(`${spec.symbol} ${low} … ${max}`);
    }
  }
  if (widened.length) notes.push(`slider ranges widened to the data's scale: ${widened.join(", ")}`);
  const others = Object.keys(fitted).filter((name) => name !== "n"
    && !specs.some((spec) => spec.name === name));
  if (others.length) notes.push(`the explorer has no control for ${others.join(", ")}`);
  return { values, notes, ranges, units: unitsOfReport(report) };
}

/** The measured points to overlay in the explorer: on the Stribeck plot (steady data),
 *  the break-away plot (break-away data) or the hysteresis loop (a time series). */
export function measuredOverlay(job) {
  const columns = job.series.columns;
  const plot = { steady: "stribeck", breakaway: "breakaway", timeseries: "hysteresis" }[job.report.kind];
  const axis = { stribeck: "v", breakaway: "k", hysteresis: "x" }[plot];
  return { plot, x: columns[axis], y: columns.measured };
}

/** The message of a bad file: the engine's sentence, with line and column if it lacks them. */
export function dataErrorMessage(error) {
  const item = error instanceof ApiError && error.detail.length ? error.detail[0] : null;
  let message = item ? item.msg : error.message;
  if (item && item.line != null && !message.includes(`line ${item.line}`)) {
    message += ` (line ${item.line}${item.column ? `, column '${item.column}'` : ""})`;
  }
  return message;
}

