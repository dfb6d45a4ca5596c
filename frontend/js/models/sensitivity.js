// Where break-away forces carry information about V and δ: the band of rates over which
// F_ba(k) changes most with them (the note's Fig. 5: the curves for the different F̂
// part only during the exponential decrease). F_ba(k) is the steady curve at the
// break-away speed ẋ* = k/(s·F̂·|ln z*|); it depends on V and δ only while ẋ* lies in
// the Stribeck drop. The band is where √((∂F_ba/∂ln V)² + (∂F_ba/∂ln δ)²) is at least
// half its largest value: the same rule as the planner's (plan/sensitivity.py), which
// tests/browser/test_browser_planner.py holds it to.

import { breakawayForce, breakawayVelocity } from "./model.js";

/** The sensitivity at the band's edges, as a share of its largest value. */
export const BAND_LEVEL = 0.5;
const DECADES = 6;
const POINTS = 1201;
const STEP = 1e-5; // relative step of the central differences in ln V and ln δ
/** The parameters the band depends on (with F̂): not the rate k, which it ranges over. */
export const BAND_PARAMS = ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba"];

/** Two sets of parameters with the same key have the same band. */
export function bandKey(p, fHat = p.F_hat) {
  return JSON.stringify([fHat, ...BAND_PARAMS.map((name) => p[name])]);
}

/** √((∂Fss/∂ln V)² + (∂Fss/∂ln δ)²) at speed `v` > 0 [N]: with y = (v/V)^δ, the drop
 *  (Fs − Fc)·e^(−y) moves by (Fs − Fc)·y·e^(−y)·δ with ln V and by −(Fs − Fc)·y·e^(−y)·ln y
 *  with ln δ. With a constant F̂, ẋ* does not depend on V or δ, and this is the
 *  sensitivity of F_ba itself: one speed a rate, where differences took four forces
 *  (a fifth of a live frame's script while Fc moved). y·e^(−y) is formed as
 *  exp(ln y − y), which a large δ does not turn into 0·Infinity. */
function dropSensitivity(v, p) {
  const logY = p.delta * (Math.log(v) - Math.log(p.V));
  const y = Math.exp(Math.min(logY, 700.0));
  return (p.Fs - p.Fc) * Math.exp(logY - y) * Math.sqrt(p.delta * p.delta + logY * logY);
}

/**
 * The band of rates for the parameters `p` ({Fc, Fs, V, delta, sigma, s, z_ba}) with
 * F̂ = `fHat`: {k: [low, high], speed: [low, high], peak} (N/s, m/s), or null without a
 * drop (Fs = Fc).
 */
export function rateBand(p, fHat = p.F_hat) {
  if (!(p.Fs > p.Fc)) return null;
  const level = fHat === "Fc" ? p.Fc : fHat === "Fs" ? p.Fs : 0.5 * (p.Fc + p.Fs);
  const centre = p.V * p.s * level * -Math.log(p.z_ba);
  const rates = new Array(POINTS);
  const strength = new Array(POINTS);
  const up = (name) => ({ ...p, [name]: p[name] * Math.exp(STEP) });
  const down = (name) => ({ ...p, [name]: p[name] * Math.exp(-STEP) });
  const [vUp, vDown, dUp, dDown] = [up("V"), down("V"), up("delta"), down("delta")];
  let peak = 0;
  for (let i = 0; i < POINTS; i += 1) {
    const k = centre * 10 ** (-DECADES + (2 * DECADES * i) / (POINTS - 1));
    rates[i] = k;
    if (fHat === "self") {
      // ẋ* itself moves with V and δ: four forces at each rate, central differences
      const byV = (breakawayForce(k, vUp, fHat) - breakawayForce(k, vDown, fHat)) / (2 * STEP);
      const byDelta = (breakawayForce(k, dUp, fHat) - breakawayForce(k, dDown, fHat)) / (2 * STEP);
      strength[i] = Math.sqrt(byV * byV + byDelta * byDelta);
    } else {
      strength[i] = dropSensitivity(breakawayVelocity(k, p, fHat), p);
    }
    if (strength[i] > strength[peak]) peak = i;
  }
  if (!(strength[peak] > 0)) return null;
  const bar = BAND_LEVEL * strength[peak];
  let low = peak;
  while (low > 0 && strength[low - 1] >= bar) low -= 1;
  let high = peak;
  while (high < POINTS - 1 && strength[high + 1] >= bar) high += 1;
  const speed = (k) => breakawayVelocity(k, p, fHat);
  return { k: [rates[low], rates[high]], speed: [speed(rates[low]), speed(rates[high])], peak: rates[peak] };
}
