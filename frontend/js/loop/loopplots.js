// The control loop on screen: pure functions from one POST /api/loop answer to the three
// figures (r and x, e, u and F over t) and the rows of the stick-phase table. Every stick
// phase is marked on the force plot: u while the body sticks, as a band under u (its mean
// slope is the rate k of the note's ramp experiment), the simulated break-away u_ba (✕)
// and the note's (E13) value at that k (◆). Nothing here touches the DOM. Colours:
// palette.js.

import {
  fmt, hover, label, quantity,
} from "../page/units.js";
import { PALETTE } from "../plots/palette.js";
import { plotLayout } from "../plots/plots.js";

/** The three plots' axis titles in the state's units, also the CSV columns of an export. */
export function loopAxes(plot, state) {
  const y = { "loop-position": label("r, x", "m", state), "loop-error": label("e = r − x", "m", state),
    "loop-force": label("u, F", "N", state) }[plot];
  return { x: "t [s]", y };
}

/** A hover label "t = … s<br>name = … unit" in the state's units. */
function atTime(name, linear, state, format = ".4g") {
  return `t = %{x:.3g} s<br>${hover(name, "y", format, linear, state)}<extra></extra>`;
}

/** Index of the sample nearest to time `t` in the sorted times `ts`. */
export function indexAt(ts, t) {
  let lo = 0;
  let hi = ts.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (ts[mid] < t) lo = mid; else hi = mid;
  }
  return Math.abs(ts[lo] - t) <= Math.abs(ts[hi] - t) ? lo : hi;
}

function layout(plot, state, duration, extra = {}) {
  const out = plotLayout(plot, loopAxes(plot, state), {
    legend: { orientation: "h", x: 0, y: -0.24, yanchor: "top" }, ...extra });
  // the three plots share the run's time axis
  out.xaxis = { ...out.xaxis, range: [0, duration] };
  return out;
}

const duration = (loop) => loop.duration ?? loop.t[loop.t.length - 1];

/** r(t) and x(t), each break-away marked on x. */
export function positionFigure(loop, state) {
  const colors = PALETTE.loopPosition;
  const phases = loop.stick_phases;
  const at = phases.map((phase) => indexAt(loop.t, phase.t_ba));
  const data = [
    { type: "scatter", mode: "lines", name: "r (reference)", x: loop.t, y: loop.r,
      line: { color: colors.r, width: 1.5, dash: "dash" },
      hovertemplate: atTime("r", "m", state) },
    { type: "scatter", mode: "lines", name: "x (position)", x: loop.t, y: loop.x,
      line: { color: colors.x, width: 2 },
      hovertemplate: atTime("x", "m", state) },
  ];
  if (phases.length) {
    data.push({
      type: "scatter", mode: "markers", name: "break-away", x: at.map((i) => loop.t[i]),
      y: at.map((i) => loop.x[i]), marker: { color: colors.breakAway, size: 8, symbol: "x" },
      hovertemplate: `break-away<br>${atTime("x", "m", state)}`,
    });
  }
  return { data, layout: layout("loop-position", state, duration(loop)) };
}

/** e(t), and the band ±amplitude of the hunting over the run's last half. */
export function errorFigure(loop, state) {
  const colors = PALETTE.loopError;
  const data = [{
    type: "scatter", mode: "lines", name: "e = r − x", x: loop.t, y: loop.e,
    line: { color: colors.e, width: 1.6 },
    hovertemplate: atTime("e", "m", state),
  }];
  const end = duration(loop);
  if (loop.hunting) {
    const a = loop.hunting.amplitude;
    data.push({
      type: "scatter", mode: "lines", name: `hunting: ±${quantity(a, "m", state)}`, x: [end / 2, end, null, end / 2, end],
      y: [a, a, null, -a, -a], line: { color: colors.band, width: 1.2, dash: "dot" },
      hovertemplate: `${hover("amplitude", "y", ".3g", "m", state)}<extra></extra>`,
    });
  }
  return { data, layout: layout("loop-error", state, end, { showlegend: Boolean(loop.hunting) }) };
}

/** u(t) and F(t), and every stick phase: u while the body sticks (a band under u), the
 *  simulated u_ba ✕ and the note's E13 ◆ at the phase's rate k (hover: both, and k). */
export function forceFigure(loop, state) {
  const colors = PALETTE.loopForce;
  const phases = loop.stick_phases;
  const sticks = { x: [], y: [] };
  for (const phase of phases) {
    const last = indexAt(loop.t, phase.t_ba);
    for (let i = indexAt(loop.t, phase.t_start); i <= last; i += 1) {
      sticks.x.push(loop.t[i]);
      sticks.y.push(loop.u[i]);
    }
    sticks.x.push(null);
    sticks.y.push(null);
  }
  const data = [
    ...(phases.length ? [{
      type: "scatter", mode: "lines", name: "stick phase: u while stuck", x: sticks.x, y: sticks.y,
      connectgaps: false, opacity: 0.35, line: { color: colors.stick, width: 7 }, hoverinfo: "skip",
    }] : []),
    { type: "scatter", mode: "lines", name: "u (controller)", x: loop.t, y: loop.u,
      line: { color: colors.u, width: 2 },
      hovertemplate: atTime("u", "N", state) },
    { type: "scatter", mode: "lines", name: "F (friction)", x: loop.t, y: loop.F,
      line: { color: colors.F, width: 1.6, dash: "dash" },
      hovertemplate: atTime("F", "N", state) },
  ];
  if (!phases.length) return { data, layout: layout("loop-force", state, duration(loop)) };
  const details = phases.map((phase, i) => [i + 1, phase.k, phase.u_ba, phase.E13]);
  const phaseHover = `phase %{customdata[0]}: t_ba = %{x:.4g} s<br>${hover("k", "customdata[1]", ".3g", "N/s", state)}`
    + `<br>${hover("u_ba", "customdata[2]", ".4g", "N", state)} (simulation)`
    + `<br>${hover("E13", "customdata[3]", ".4g", "N", state)} (F̂ = ${state.F_hat})<extra></extra>`;
  data.push({
    type: "scatter", mode: "markers", name: "u_ba (simulated)", x: phases.map((p) => p.t_ba),
    y: phases.map((p) => p.u_ba), customdata: details,
    marker: { color: colors.breakAway, size: 9, symbol: "x" }, hovertemplate: phaseHover,
  });
  const predicted = phases.map((phase, i) => [phase, details[i]]).filter(([phase]) => phase.E13 != null);
  if (predicted.length) {
    data.push({
      type: "scatter", mode: "markers", name: `E13 at k (F̂ = ${state.F_hat})`,
      x: predicted.map(([p]) => p.t_ba), y: predicted.map(([p]) => p.E13),
      customdata: predicted.map(([, d]) => d),
      marker: { color: colors.e13, size: 8, symbol: "diamond" }, hovertemplate: phaseHover,
    });
  }
  return { data, layout: layout("loop-force", state, duration(loop)) };
}

/** The three figures of one answer, keyed by plot id. */
export function loopFigures(loop, state) {
  return {
    "loop-position": positionFigure(loop, state),
    "loop-error": errorFigure(loop, state),
    "loop-force": forceFigure(loop, state),
  };
}

/** The stick-phase table's rows: the simulated break-away beside E13 at its rate. */
export function phaseRows(loop) {
  return loop.stick_phases.map((phase, i) => ({
    phase: i + 1,
    t_ba: fmt(phase.t_ba, 4),
    k: fmt(phase.k),
    u_ba: fmt(phase.u_ba, 4),
    E13: fmt(phase.E13, 4),
    difference: phase.E13 == null ? "–"
      : `${fmt((100 * (Math.abs(phase.E13) - Math.abs(phase.u_ba))) / Math.abs(phase.u_ba), 2)} %`,
  }));
}
