// Teaching tools as pure functions: pinned reference curves, parameter sweeps and the
// guided tour through the note's figures. lessons.js owns the state and the requests.

import { SWEEP } from "../plots/palette.js";
import { hover, quantity } from "../page/units.js";

/** Faded copies of a figure's traces, to keep as a reference while the sliders move. */
export function pinnedTraces(figure) {
  return figure.data
    .filter((trace) => trace.name !== "simulation" && !String(trace.name).startsWith("pinned"))
    .map((trace, i) => ({
      ...trace,
      name: i === 0 ? "pinned" : `pinned: ${trace.name}`,
      legendgroup: "pinned",
      showlegend: i === 0,
      opacity: 0.3,
      hoverinfo: "skip",
      hovertemplate: undefined,
      line: trace.line ? { ...trace.line, dash: "dot" } : undefined,
    }));
}

/** A figure with extra traces appended (figures are fresh objects: no mutation). */
export function withTraces(figure, traces) {
  return traces.length ? { ...figure, data: [...figure.data, ...traces] } : figure;
}


/**
 * `count` values of `name` around the current state, none of them the current value:
 * count + 1 evenly spaced over the sweep's range (a factor 4 around the value for the
 * log-scale parameters, halved to doubled; ±1 for δ; 0.5 … 0.99 for z*), then the one
 * equal to the current value dropped, or else the one farthest from it (the last when
 * two are). Fc stays at or below Fs and Fs at or above Fc (the model needs Fs ≥ Fc).
 */
export function sweepValues(name, state, count = 5) {
  const value = Number(state[name]);
  const round = (v) => Number(v.toPrecision(4));
  let [lo, hi, log] = [value / 2, 2 * value, true];
  if (name === "Fc") hi = Math.min(2 * value, Number(state.Fs));
  else if (name === "Fs") lo = Math.max(value / 2, Number(state.Fc));
  else if (name === "delta") [lo, hi, log] = [value - 1, value + 1, false];
  else if (name === "z_ba") [lo, hi, log] = [0.5, 0.99, false];
  else if (name === "sigma" && !(value > 0)) [lo, hi, log] = [0, 0.002, false];
  const n = count + 1;
  let values = Array.from({ length: n }, (_, i) => (log
    ? lo * (hi / lo) ** (i / (n - 1)) : lo + ((hi - lo) * i) / (n - 1)));
  if (name === "delta") values = values.map((d) => (Math.abs(d) < 0.05 ? 0.05 * Math.sign(d || 1) : d));
  values = [...new Set(values.map(round))].filter((v) => v !== round(value));
  const distance = (v) => (log ? Math.abs(Math.log(v / value)) : Math.abs(v - value));
  while (values.length > count) {
    const far = values.reduce((best, v, i) => (distance(v) >= distance(values[best]) ? i : best), 0);
    values.splice(far, 1);
  }
  return values;
}

/** Whether two curves are the same up to the served frame's float32 rounding. */
function sameCurve(a, b) {
  if (a.length !== b.length) return false;
  let scale = 0;
  for (const v of b) if (Number.isFinite(v)) scale = Math.max(scale, Math.abs(v));
  return a.every((v, i) => Math.abs(v - b[i]) <= 1e-6 * scale || (!Number.isFinite(v) && !Number.isFinite(b[i])));
}

/** The curve of `frame` that each plot's sweep shows: Fss(v), the loop, the phase curve
 *  of the current k, the break-away curve of the chosen F̂; its axes [name, linear unit]. */
const SWEPT = {
  stribeck: (frame) => ({ x: frame.stribeck.v, y: frame.stribeck.F, axes: [["v", "m/s"], ["Fss", "N"]] }),
  hysteresis: (frame) => ({ x: frame.hysteresis.x, y: frame.hysteresis.F, axes: [["x", "m"], ["F", "N"]] }),
  phase: (frame) => ({ x: frame.phase.z, y: frame.phase.curves[frame.phase.curves.length - 1].v, axes: [["z", ""], ["ẋ", "m/s"]] }),
  breakaway: (frame, state) => ({ x: frame.breakaway.k, y: frame.breakaway[state.F_hat], axes: [["k", "N/s"], ["F_ba", "N"]] }),
};

/**
 * The plots a sweep shows on: those where every swept curve differs from the curve of
 * `frame` (the state swept from): a sweep of V leaves the loop as it is, a sweep of k
 * the Stribeck curve, the loop and the break-away curve.
 */
export function sweptPlots(sweep, state, frame) {
  return Object.keys(SWEPT).filter((plot) => {
    const current = SWEPT[plot](frame, state);
    return sweep.frames.every((swept) => {
      const curve = SWEPT[plot](swept, state);
      return !(sameCurve(curve.y, current.y) && sameCurve(curve.x, current.x));
    });
  });
}

/** The swept curves on each plot of `sweep.plots`. */
export function sweepTraces(sweep, state, label) {
  const out = {};
  for (const plot of sweep.plots) {
    const curves = sweep.frames.map((swept) => SWEPT[plot](swept, state));
    out[plot] = curves.map((curve, i) => {
      const name = `${label} = ${sweep.values[i]}`;
      const [[x, xUnit], [y, yUnit]] = curve.axes;
      const hovered = `${hover(x, "x", ".3g", xUnit, state)}<br>${hover(y, "y", ".4g", yUnit, state)}`;
      return { type: "scatter", mode: "lines", name, legendgroup: `sweep-${i}`, x: curve.x, y: curve.y,
        line: { color: SWEEP[i % SWEEP.length], width: 1.6 },
        hovertemplate: `${name}<br>${hovered}<extra></extra>` };
    });
  }
  return out;
}

/** Where the documentation (served under /guide/) explains what each kind of tour step
 *  shows: a section's address and its title. */
export const TOUR_DOCS = {
  stribeck: { href: "model.html#steady-state-the-stribeck-curve-e2",
    title: "the Stribeck curve (E2)" },
  hysteresis: { href: "model.html#presliding-with-reversal-memory-e3e6",
    title: "presliding with reversal memory (E3–E6′)" },
  phase: { href: "model.html#the-break-away-curve-e7e13", title: "the break-away curve (E7–E13)" },
  breakaway: { href: "model.html#the-break-away-curve-e7e13",
    title: "the break-away curve (E7–E13)" },
  ramp: { href: "ramp.html#where-the-simulation-and-e13-agree-and-where-they-do-not",
    title: "the ramp experiment, simulated" },
  loop: { href: "control-loop.html#stick-phases-and-hunting", title: "friction in a control loop" },
};

/**
 * The guided tour through the note's figures: each step sets parameters (a preset and
 * overrides), says what to look at (in the state's units: `text(state)`), names the
 * plot it is about and may sweep a parameter over it.
 */
export const TOUR = [
  { preset: "fig5", set: { k: 1 }, plot: "stribeck", sweep: "V",
    text: (state) => `Fig. 4, the Stribeck curve (E2): friction falls from the stiction level Fs = `
      + `${quantity(1.5, "N", state)} to the Coulomb level Fc = ${quantity(1, "N", state)} as the sliding `
      + "speed grows. V sets where it falls: the thin curves are the same model at five other V." },
  { preset: "fig5", set: { k: 1, s: 1 }, plot: "hysteresis", sweep: "s",
    text: () => "Fig. 1, presliding (E4–E6′): after each reversal the force builds up along "
      + "f(z) = z(1 − ln z) over the presliding distance 1/s; every reversal starts a new "
      + "branch, so inner loops nest inside the outer one. The thin loops are five other s." },
  { preset: "fig5", set: { k: 0.01 }, plot: "phase",
    text: (state) => "Fig. 3, the phase family (E12): ẋ(z) = −k/(s·F̂·ln z). At a slow ramp "
      + `(k = ${quantity(0.01, "N/s", state)}) the presliding velocity at z* stays tiny.` },
  { preset: "fig5", set: { k: 20 }, plot: "phase",
    text: (state) => `Fig. 3 again at k = ${quantity(20, "N/s", state)}: the curve rises by three `
      + "decades. A fast ramp reaches z* at a high velocity, where the Stribeck curve has already fallen." },
  { preset: "fig5", set: { k: 4 }, plot: "breakaway",
    text: (state) => "Fig. 5, the break-away curve (E13): F_ba(k) = Fss(ẋ(z*)) falls from Fs towards "
      + `Fc as k grows. The four F̂ choices differ most around k ≈ ${quantity(4, "N/s", state)}.` },
  { preset: "fig5", set: { k: 4 }, plot: "ramp",
    text: () => "The ramp experiment below simulates m·ẍ + F = k·t. Its break-away force rises "
      + "with k while E13 falls: E13 drops the ∂F/∂ẋ·ẍ term and the inertia. Press Play." },
  { preset: "viscous", set: { k: 10 }, plot: "breakaway",
    text: () => "With viscous friction σ the break-away curve dips and then rises again at high "
      + "rates: σ·ẋ* grows linearly with k." },
  { preset: "fig5", set: { k: 4 }, reset: "loop", plot: "loop",
    text: () => "The control loop: a PID position loop on the same friction hunts. While the body "
      + "sticks, the integral term ramps u as in the ramp experiment until it breaks away (✕; "
      + "E13 ◆ says where); sliding, friction falls from Fs towards Fc and the body overshoots. "
      + "The sentence under the plots gives the numbers." },
  { preset: "no-stribeck", set: { k: 4 }, reset: "loop", plot: "loop",
    text: () => "The same loop with Fs = Fc: friction no longer falls once the body slides, so "
      + "nothing overshoots and the loop settles. Move Ki and Kd, try a sine and compensation: "
      + "the sentence says what each changes." },
];

/** The state of tour step `index`, from the presets and the current state; a step that
 *  resets a view's part of the state takes `partDefaults(name)` (state.js). */
export function tourState(index, presets, state, partDefaults = () => ({})) {
  const step = TOUR[index];
  const preset = presets.find((p) => p.name === step.preset);
  return {
    ...state, ...(step.reset ? partDefaults(step.reset) : {}), ...(preset ? preset.params : {}), ...step.set,
  };
}
