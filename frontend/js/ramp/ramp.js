// The ramp experiment on screen: pure functions from one POST /api/ramp answer to the
// ramp figure, the simulated path over the phase family, and the sentence that explains
// the break-away numbers. Nothing here touches the DOM.

import { PALETTE } from "../plots/palette.js";

const COLORS = PALETTE.ramp;

function fmt(value, digits = 3) {
  if (value == null || !Number.isFinite(value)) return "–";
  return String(Number(value.toPrecision(digits)));
}

/** u(t) = k·t and F(t) on the left axis, ẋ(t) on the right, the break-away instant
 *  marked, and the E13 level as a dotted line for comparison. */
export function rampFigure(ramp, state, cursor = null) {
  const data = [
    { type: "scatter", mode: "lines", name: "u = k·t (actuation)", x: ramp.t, y: ramp.u,
      line: { color: COLORS.u, width: 2 },
      hovertemplate: "t = %{x:.3g} s<br>u = %{y:.4g} N<extra></extra>" },
    { type: "scatter", mode: "lines", name: "F (friction)", x: ramp.t, y: ramp.F,
      line: { color: COLORS.F, width: 2, dash: "dash" },
      hovertemplate: "t = %{x:.3g} s<br>F = %{y:.4g} N<extra></extra>" },
    { type: "scatter", mode: "lines", name: "ẋ (right axis)", x: ramp.t, y: ramp.v,
      yaxis: "y2", line: { color: COLORS.v, width: 1.2 },
      hovertemplate: "t = %{x:.3g} s<br>ẋ = %{y:.3g} m/s<extra></extra>" },
  ];
  const tEnd = ramp.t.length ? ramp.t[ramp.t.length - 1] : 1;
  data.push({
    type: "scatter", mode: "lines", name: `E13: ${fmt(ramp.E13)} N`,
    x: [0, tEnd], y: [ramp.E13, ramp.E13], hoverinfo: "skip",
    line: { color: COLORS.e13, width: 1.5, dash: "dot" },
  });
  if (ramp.t_ba != null) {
    data.push({
      type: "scatter", mode: "markers+text", name: `break-away: t = ${fmt(ramp.t_ba)} s`,
      x: [ramp.t_ba], y: [ramp.u_ba], text: ["break-away"], textposition: "top left",
      marker: { color: COLORS.breakAway, size: 10, symbol: "x" },
      hovertemplate: "t_ba = %{x:.4g} s<br>u_ba = %{y:.4g} N<extra></extra>",
    });
  }
  if (cursor != null) {
    const i = nearestIndex(ramp.t, cursor);
    data.push({
      type: "scatter", mode: "markers", name: "time cursor", showlegend: false,
      x: [ramp.t[i], ramp.t[i]], y: [ramp.u[i], ramp.F[i]], hoverinfo: "skip",
      marker: { color: COLORS.breakAway, size: 9, symbol: "circle-open", line: { width: 2 } },
    });
  }
  const layout = {
    uirevision: "ramp",
    margin: { l: 58, r: 58, t: 8, b: 42 },
    font: { size: 11 },
    hovermode: "closest",
    legend: { orientation: "h", x: 0, y: -0.22, yanchor: "top" },
    xaxis: { title: { text: "t [s]", standoff: 4 } },
    yaxis: { title: { text: "u, F [N]", standoff: 4 } },
    yaxis2: { title: { text: "ẋ [m/s]", standoff: 4 }, overlaying: "y", side: "right",
      showgrid: false },
  };
  return { data, layout };
}

/** The simulated path (z, ẋ) to draw over the E12 family (positive ẋ only: log axis). */
export function simulationPhaseTrace(ramp, cursor = null) {
  const z = [];
  const v = [];
  const end = cursor == null ? ramp.t.length : nearestIndex(ramp.t, cursor) + 1;
  // the chatter's tiny velocities would stretch the log axis over decades: the path is
  // drawn from 1e-4 of its largest velocity up
  const floor = 1e-4 * Math.max(...ramp.v.filter(Number.isFinite));
  for (let i = 0; i < end; i += 1) {
    if (ramp.v[i] > floor && ramp.z[i] <= 1) {
      z.push(ramp.z[i]);
      v.push(ramp.v[i]);
    } else if (z.length && z[z.length - 1] !== null) {
      z.push(null);
      v.push(null);
    }
  }
  return {
    type: "scatter", mode: "lines", name: "simulation", x: z, y: v, connectgaps: false,
    line: { color: PALETTE.phase.simulation, width: 2 },
    hovertemplate: "simulation<br>z = %{x:.3f}<br>ẋ = %{y:.3g} m/s<extra></extra>",
  };
}

export function nearestIndex(values, target) {
  let best = 0;
  for (let i = 1; i < values.length; i += 1) {
    if (Math.abs(values[i] - target) < Math.abs(values[best] - target)) best = i;
  }
  return best;
}

/**
 * One or two sentences with the current numbers: where the simulated ramp breaks away,
 * what E13 says, the difference, and why they differ.
 */
export function explainBreakaway(ramp, state) {
  const k = fmt(Number(ramp.k ?? state.k));
  if (ramp.u_ba == null) {
    return `At k = ${k} N/s the simulated ramp did not break away within the step budget; `
      + `E13 says ${fmt(ramp.E13)} N.`;
  }
  const diff = (100 * (ramp.E13 - ramp.u_ba)) / ramp.u_ba;
  const sign = diff >= 0 ? "+" : "−";
  let why;
  if (Math.abs(diff) < 1) {
    why = "They agree: at this rate the presliding is slow enough that the ∂F/∂ẋ·ẍ term and "
      + "the inertia m·ẍ that E13 drops hardly matter.";
  } else if (ramp.reversals > 0) {
    why = `They differ because E13 drops the ∂F/∂ẋ·ẍ term: with velocity weakening the `
      + `quasi-static branch is unstable, and the simulated body chattered through `
      + `${ramp.reversals} reversal${ramp.reversals === 1 ? "" : "s"} before it slipped.`;
  } else if (diff < 0) {
    why = "They differ because E13 drops the inertia m·ẍ and the ∂F/∂ẋ·ẍ term: the ramp "
      + "cannot accelerate the mass to E12's break-away velocity in time, so the friction "
      + "is still high when the body breaks away, and u = F + m·ẍ adds the inertial share.";
  } else {
    why = "They differ because E13 drops the ∂F/∂ẋ·ẍ term and the inertia m·ẍ.";
  }
  return `At k = ${k} N/s the simulation breaks away at u = ${fmt(ramp.u_ba)} N `
    + `(t_ba = ${fmt(ramp.t_ba)} s, friction ${fmt(ramp.F_ba)} N); E13 with F̂ = `
    + `${state.F_hat} says ${fmt(ramp.E13)} N (${sign}${fmt(Math.abs(diff), 2)} %). ${why}`;
}

/** The body of POST /api/ramp for the explorer's state. */
export function rampBody(state) {
  const body = { k: Number(state.k), F_hat: state.F_hat, max_steps: 300_000 };
  for (const name of ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "m"]) {
    body[name] = Number(state[name]);
  }
  return body;
}
