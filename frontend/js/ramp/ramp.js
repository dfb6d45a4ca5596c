// The ramp experiment on screen: pure functions from one POST /api/ramp answer to the
// ramp figure, the simulated path over the phase family, and the sentence that explains
// the break-away numbers, in the state's units. Nothing here touches the DOM.

import { breakawayVelocity, steadyForce } from "../models/model.js";
import {
  fmt, hover, label, quantity,
} from "../page/units.js";
import { PALETTE } from "../plots/palette.js";

const COLORS = PALETTE.ramp;

/** The ramp plot's axis titles in the state's units (its CSV columns: ẋ on the right). */
export function rampAxes(state) {
  return { x: "t [s]", y: label("u, F", "N", state), y2: label("ẋ", "m/s", state) };
}

/** u(t) = k·t and F(t) on the left axis, ẋ(t) on the right, the break-away instant
 *  marked, and the E13 level as a dotted line for comparison. */
export function rampFigure(ramp, state, cursor = null) {
  const at = (name, linear, format) => `t = %{x:.3g} s<br>${hover(name, "y", format, linear, state)}<extra></extra>`;
  const data = [
    { type: "scatter", mode: "lines", name: "u = k·t (actuation)", x: ramp.t, y: ramp.u,
      line: { color: COLORS.u, width: 2 }, hovertemplate: at("u", "N", ".4g") },
    { type: "scatter", mode: "lines", name: "F (friction)", x: ramp.t, y: ramp.F,
      line: { color: COLORS.F, width: 2, dash: "dash" }, hovertemplate: at("F", "N", ".4g") },
    { type: "scatter", mode: "lines", name: "ẋ (right axis)", x: ramp.t, y: ramp.v,
      yaxis: "y2", line: { color: COLORS.v, width: 1.2 }, hovertemplate: at("ẋ", "m/s", ".3g") },
  ];
  const tEnd = ramp.t.length ? ramp.t[ramp.t.length - 1] : 1;
  data.push({
    type: "scatter", mode: "lines", name: `E13: ${quantity(ramp.E13, "N", state)}`,
    x: [0, tEnd], y: [ramp.E13, ramp.E13], hoverinfo: "skip",
    line: { color: COLORS.e13, width: 1.5, dash: "dot" },
  });
  if (ramp.t_ba != null) {
    data.push({
      type: "scatter", mode: "markers+text", name: `break-away: t = ${fmt(ramp.t_ba)} s`,
      x: [ramp.t_ba], y: [ramp.u_ba], text: ["break-away"], textposition: "top left",
      marker: { color: COLORS.breakAway, size: 10, symbol: "x" },
      hovertemplate: `t_ba = %{x:.4g} s<br>${hover("u_ba", "y", ".4g", "N", state)}<extra></extra>`,
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
  const axes = rampAxes(state);
  const layout = {
    uirevision: "ramp",
    margin: { l: 58, r: 58, t: 8, b: 42 },
    font: { size: 11 },
    hovermode: "closest",
    legend: { orientation: "h", x: 0, y: -0.22, yanchor: "top" },
    xaxis: { title: { text: axes.x, standoff: 4 } },
    yaxis: { title: { text: axes.y, standoff: 4 } },
    yaxis2: { title: { text: axes.y2, standoff: 4 }, overlaying: "y", side: "right",
      showgrid: false },
  };
  return { data, layout };
}

/** The simulated path (z, ẋ) to draw over the E12 family (positive ẋ only: log axis). */
export function simulationPhaseTrace(ramp, state, cursor = null) {
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
    hovertemplate: `simulation<br>z = %{x:.3f}<br>${hover("ẋ", "y", ".3g", "m/s", state)}<extra></extra>`,
  };
}

export function nearestIndex(values, target) {
  let best = 0;
  for (let i = 1; i < values.length; i += 1) {
    if (Math.abs(values[i] - target) < Math.abs(values[best] - target)) best = i;
  }
  return best;
}

/** Shares below this part of u_ba are not named as a reason (half of the 1 % within
 *  which the two are said to agree, so that a difference always has a named reason). */
const MINOR = 0.005;

/**
 * The sentences under the ramp, each built from the run's facts: where the simulation
 * breaks away (u_ba, its friction and the inertial share m·ẍ = u − F), what E13 says
 * and how far apart they are, and why: only the reasons this run shows, each with its
 * number (the inertia E13 leaves out; the speed at z*, which E12 gets wrong by leaving
 * out inertia and the change of F̂ with ẋ, and the steady friction there; presliding
 * not yet at the steady level; the chatter of reversals before the slip).
 */
export function explainBreakaway(ramp, state) {
  const p = { ...rampBody(state), ...(ramp.params ?? {}) };
  const k = Number(ramp.k ?? p.k);
  const q = (value, linear) => quantity(value, linear, state);
  if (ramp.u_ba == null) {
    return `At k = ${q(k, "N/s")} the simulated ramp did not break away within the step budget; `
      + `E13 says ${q(ramp.E13, "N")}.`;
  }
  const u = ramp.u_ba;
  const inertia = u - ramp.F_ba;
  const gap = (ramp.E13 - u) / u;
  const facts = `At k = ${q(k, "N/s")} the simulation breaks away at u = ${q(u, "N")} `
    + `(t_ba = ${q(ramp.t_ba, "s")}): friction ${q(ramp.F_ba, "N")} and m·ẍ = ${q(inertia, "N")} `
    + `accelerating the mass. E13 with F̂ = ${p.F_hat} says ${q(ramp.E13, "N")}, ${apart(gap)}.`;
  const reasons = [];
  if (Math.abs(inertia) >= MINOR * Math.abs(u)) {
    reasons.push(`E13 has no inertia, and m·ẍ is ${fmt(100 * Math.abs(inertia / u), 2)} % of u_ba`);
  }
  const vBa = ramp.v[nearestIndex(ramp.t, ramp.t_ba)];
  const vE12 = breakawayVelocity(k, p, p.F_hat);
  const steadyAtBa = steadyForce(vBa, p);
  if (Math.abs(steadyAtBa - ramp.E13) >= MINOR * Math.abs(u)) {
    reasons.push(`the body reaches z* at ẋ = ${q(vBa, "m/s")}, not at E12's ${q(vE12, "m/s")} `
      + "(E12 leaves out inertia and the change of F̂ with ẋ), and the steady friction there is "
      + `${q(steadyAtBa, "N")}, not E13's ${q(ramp.E13, "N")}`);
  }
  if (Math.abs(ramp.F_ba - steadyAtBa) >= MINOR * Math.abs(u)) {
    reasons.push(`at z* = ${fmt(p.z_ba)} the presliding friction, ${q(ramp.F_ba, "N")}, has not `
      + `reached the steady ${q(steadyAtBa, "N")} that E13 takes`);
  }
  if (Math.abs(gap) < 0.01) {
    // within 1 %: what E13 leaves out is small here, or its parts offset each other
    const offset = reasons.length > 1 ? `, although ${reasons.join("; and ")}: these offset each other` : "";
    return `${facts} They agree within 1 %${offset}.`;
  }
  let why = reasons.length ? `They differ because ${reasons.join("; and ")}.` : "";
  if (ramp.reversals > 0) {
    const weakening = p.Fs > p.Fc && p.delta > 0;
    why += ` The simulated body chattered through ${ramp.reversals} reversal`
      + `${ramp.reversals === 1 ? "" : "s"} before it slipped`
      + (weakening ? ": with velocity weakening the quasi-static branch is unstable."
        : ": the mass oscillates on the presliding stiffness.");
  }
  return `${facts} ${why.trim()}`.trim();
}

/** How far E13 lies from u_ba: a percentage while they are of a size, else a factor. */
function apart(gap) {
  if (Math.abs(gap) <= 0.5) return `${gap >= 0 ? "+" : "−"}${fmt(100 * Math.abs(gap), 2)} % from u_ba`;
  const ratio = 1 + gap; // E13 / u_ba
  return ratio > 1 ? `${fmt(ratio, 2)} times u_ba` : `1/${fmt(1 / ratio, 2)} of u_ba`;
}

/** The body of POST /api/ramp for the explorer's state. */
export function rampBody(state) {
  const body = { k: Number(state.k), F_hat: state.F_hat, max_steps: 300_000 };
  for (const name of ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "m"]) {
    body[name] = Number(state[name]);
  }
  return body;
}
