// Teaching tools as pure functions: pinned reference curves, parameter sweeps and the
// guided tour through the note's figures. main.js owns the state and the requests.

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

const SWEEP_COLORS = ["#08306b", "#2171b5", "#6baed6", "#fd8d3c", "#d94801", "#7f2704", "#3f007d"];

/**
 * Evenly spaced values of `name` around the current state: a factor 4 around the value
 * for the log-scale parameters (halved to doubled), ±1 for δ, 0.5 … 0.99 for z*; Fc stays
 * at or below Fs and Fs at or above Fc (MODEL.md §1).
 */
export function sweepValues(name, state, count = 5) {
  const value = Number(state[name]);
  const geometric = (lo, hi) => Array.from({ length: count },
    (_, i) => lo * (hi / lo) ** (i / (count - 1)));
  const linear = (lo, hi) => Array.from({ length: count }, (_, i) => lo + ((hi - lo) * i) / (count - 1));
  const round = (v) => Number(v.toPrecision(4));
  let values;
  if (name === "Fc") values = geometric(value / 2, Math.min(2 * value, Number(state.Fs)));
  else if (name === "Fs") values = geometric(Math.max(value / 2, Number(state.Fc)), 2 * value);
  else if (name === "delta") {
    values = linear(value - 1, value + 1).map((d) => (Math.abs(d) < 0.05 ? 0.05 * Math.sign(d || 1) : d));
  } else if (name === "z_ba") values = linear(0.5, 0.99);
  else if (name === "sigma") values = value > 0 ? geometric(value / 2, 2 * value) : linear(0, 0.002);
  else values = geometric(value / 2, 2 * value);
  return [...new Set(values.map(round))];
}

/** The swept curves on the break-away plot (the chosen F̂) and the hysteresis loop. */
export function sweepTraces(sweep, state, label) {
  const breakaway = [];
  const hysteresis = [];
  sweep.frames.forEach((frame, i) => {
    const name = `${label} = ${sweep.values[i]}`;
    const color = SWEEP_COLORS[i % SWEEP_COLORS.length];
    breakaway.push({ type: "scatter", mode: "lines", name, legendgroup: `sweep-${i}`,
      x: frame.breakaway.k, y: frame.breakaway[state.F_hat], line: { color, width: 1.6 },
      hovertemplate: `${name}<br>k = %{x:.3g} N/s<br>F_ba = %{y:.4g} N<extra></extra>` });
    hysteresis.push({ type: "scatter", mode: "lines", name, legendgroup: `sweep-${i}`,
      x: frame.hysteresis.x, y: frame.hysteresis.F, line: { color, width: 1.2 },
      hovertemplate: `${name}<br>x = %{x:.3g} m<br>F = %{y:.3g} N<extra></extra>` });
  });
  return { breakaway, hysteresis };
}

/**
 * The guided tour through the note's figures: each step sets parameters (a preset and
 * overrides) and says what to look at.
 */
export const TOUR = [
  { preset: "fig5", set: { k: 1 },
    text: "Fig. 4, the Stribeck curve (E2): friction falls from the stiction level Fs = 1.5 "
      + "to the Coulomb level Fc = 1 as the sliding speed grows. V sets where it falls." },
  { preset: "fig5", set: { k: 1, s: 1 },
    text: "Fig. 1, presliding (E4–E6′): after each reversal the force builds up along "
      + "f(z) = z(1 − ln z) over the presliding distance 1/s; every reversal starts a new "
      + "branch, so inner loops nest inside the outer one." },
  { preset: "fig5", set: { k: 0.01 },
    text: "Fig. 3, the phase family (E12): ẋ(z) = −k/(s·F̂·ln z). At a slow ramp "
      + "(k = 0.01 N/s) the presliding velocity at z* stays tiny." },
  { preset: "fig5", set: { k: 20 },
    text: "Fig. 3 again at k = 20 N/s: the curve rises by three decades. A fast ramp reaches "
      + "z* at a high velocity, where the Stribeck curve has already fallen." },
  { preset: "fig5", set: { k: 4 },
    text: "Fig. 5, the break-away curve (E13): F_ba(k) = Fss(ẋ(z*)) falls from Fs towards "
      + "Fc as k grows. The four F̂ choices differ most around k ≈ 4 N/s." },
  { preset: "fig5", set: { k: 4 },
    text: "The ramp experiment below simulates m·ẍ + F = k·t. Its break-away force rises "
      + "with k while E13 falls: E13 drops the ∂F/∂ẋ·ẍ term and the inertia. Press Play." },
  { preset: "viscous", set: { k: 10 },
    text: "With viscous friction σ the break-away curve dips and then rises again at high "
      + "rates: σ·ẋ* grows linearly with k." },
];

/** The state of tour step `index`, from the presets and the current state. */
export function tourState(index, presets, state) {
  const step = TOUR[index];
  const preset = presets.find((p) => p.name === step.preset);
  return { ...state, ...(preset ? preset.params : {}), ...step.set };
}
