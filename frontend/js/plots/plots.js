// Pure functions from one /api/explore frame (and the simulation results) to fresh
// Plotly figures {data, layout}, titled and hovered in the state's units (units.js).
// Nothing here touches the DOM; the render path hands the figures to the plots.
// Colours: palette.js.

import { hover, label, unit } from "../page/units.js";
import { DARK_INK, PALETTE } from "./palette.js";

export const PLOT_IDS = ["stribeck", "hysteresis", "phase", "breakaway"];

const COLORS = PALETTE.breakaway;

const F_HAT_DASH = { Fc: "solid", Fs: "dash", avg: "solid", self: "dot" };

const F_HAT_LABEL = { Fc: "F̂ = Fc", Fs: "F̂ = Fs", avg: "F̂ = avg", self: "F̂ = self" };

/** Axis titles of `plot` in the state's units, also the CSV columns of its export. */
export function plotAxes(plot, state) {
  const named = (symbol, linear) => label(symbol, linear, state);
  switch (plot) {
    case "stribeck": return { x: named("v", "m/s"), y: named("Fss", "N") };
    case "hysteresis": return { x: named("x", "m"), y: named("F", "N") };
    case "phase": return { x: "z [-]", y: named("ẋ", "m/s") };
    default: return { x: named("k", "N/s"), y: named("F_ba", "N") };
  }
}

/** Hover lines "k = … N/s<br>F_ba = … N" of a plot's axes in the state's units. */
function hoverXY(state, [x, xUnit, xFormat], [y, yUnit, yFormat]) {
  return `${hover(x, "x", xFormat, xUnit, state)}<br>${hover(y, "y", yFormat, yUnit, state)}`;
}

/** The layout the explorer's plots start from: fixed margins, the axes titled `axes`
 *  ({x, y}), a person's zoom kept across redraws; `extra` replaces whole keys. */
export function plotLayout(plot, axes, extra = {}) {
  return {
    uirevision: plot, // keeps a person's zoom across redraws
    margin: { l: 58, r: 12, t: 8, b: 42 },
    font: { size: 11 },
    hovermode: "closest",
    showlegend: true,
    legend: { x: 1, xanchor: "right", y: 1, bgcolor: "rgba(255,255,255,0.75)" },
    // fixed margins: automargin would cost a second layout pass on every redraw
    xaxis: { title: { text: axes.x, standoff: 4 }, zeroline: true },
    yaxis: { title: { text: axes.y, standoff: 4 }, zeroline: true, exponentformat: "power" },
    ...extra,
  };
}

function baseLayout(plot, state, extra = {}) {
  return plotLayout(plot, plotAxes(plot, state), extra);
}

export function stribeckFigure(frame, state) {
  const data = [{
    type: "scatter", mode: "lines", name: "Fss(v)",
    x: frame.stribeck.v, y: frame.stribeck.F,
    line: { color: PALETTE.stribeck.curve, width: 2 },
    hovertemplate: `${hoverXY(state, ["v", "m/s", ".3g"], ["Fss", "N", ".4g"])}<extra></extra>`,
  }];
  return { data, layout: baseLayout("stribeck", state, { showlegend: false }) };
}

/** Arrays a figure derives from a frame's curves, by the curves' object: a live frame
 *  whose curves stay (a drag of k, z* or m leaves the loop as it is) gets the same
 *  arrays, which the drawing then knows unchanged without comparing them point by
 *  point, and which are not made again. */
const derived = new WeakMap();

function derivedOf(source, make) {
  if (!derived.has(source)) derived.set(source, make());
  return derived.get(source);
}

/** The loop split into its branches by the direction of travel, and its arrowheads. */
function loopBranches({ x, F }) {
  const forward = { x: [], y: [] };
  const backward = { x: [], y: [] };
  const arrows = { x: [], y: [], symbol: [] };
  const every = Math.max(1, Math.floor(x.length / 24));
  let previous = 0;
  for (let i = 1; i < x.length; i += 1) {
    const dir = Math.sign(x[i] - x[i - 1]) || previous;
    const branch = dir > 0 ? forward : backward;
    const other = dir > 0 ? backward : forward;
    if (dir !== previous) {
      // start the branch at the reversal point, and break the other one there
      branch.x.push(x[i - 1]);
      branch.y.push(F[i - 1]);
      other.x.push(null);
      other.y.push(null);
    }
    branch.x.push(x[i]);
    branch.y.push(F[i]);
    if (i % every === 0) {
      arrows.x.push(x[i]);
      arrows.y.push(F[i]);
      arrows.symbol.push(dir > 0 ? "triangle-right" : "triangle-left");
    }
    previous = dir;
  }
  return { forward, backward, arrows, arrowColors: arrows.symbol.map(
    (s) => (s === "triangle-right" ? PALETTE.hysteresis.forward : PALETTE.hysteresis.backward)) };
}

/** The loop's branches coloured by the direction of travel (blue moving +x, orange
 *  moving −x: a colour-blind-safe pair), with arrowheads along them. */
export function hysteresisFigure(frame, state) {
  const hovered = hoverXY(state, ["x", "m", ".3g"], ["F", "N", ".3g"]);
  const { forward, backward, arrows, arrowColors } = derivedOf(frame.hysteresis, () => loopBranches(frame.hysteresis));
  const data = [
    { type: "scatter", mode: "lines", name: "moving +x", x: forward.x, y: forward.y,
      connectgaps: false, line: { color: PALETTE.hysteresis.forward, width: 1.8 },
      hovertemplate: `moving +x<br>${hovered}<extra></extra>` },
    { type: "scatter", mode: "lines", name: "moving −x", x: backward.x, y: backward.y,
      connectgaps: false, line: { color: PALETTE.hysteresis.backward, width: 1.8 },
      hovertemplate: `moving −x<br>${hovered}<extra></extra>` },
    { type: "scatter", mode: "markers", name: "direction of travel", x: arrows.x, y: arrows.y,
      hoverinfo: "skip", showlegend: false,
      marker: { symbol: arrows.symbol, size: 8, color: arrowColors } },
  ];
  const layout = baseLayout("hysteresis", state, {
    legend: { x: 0, xanchor: "left", y: 1, bgcolor: "rgba(255,255,255,0.75)" },
  });
  return { data, layout };
}

/** The family's curves as one trace's points, gaps between them: made again only when
 *  z or one of the curves is another object (a drag of k keeps them). */
function familyTrace(z, family) {
  const kept = family.length ? derived.get(family[0]) : null;
  if (kept && kept.z === z && kept.family.length === family.length
      && kept.family.every((curve, i) => curve === family[i])) return kept.value;
  // arrays of their final length, filled in place (grown push by push, they were the
  // largest thing a drag of Fc allocated)
  const length = family.length * (z.length + 1);
  const xs = new Array(length);
  const ys = new Array(length);
  const ks = new Array(length);
  let at = 0;
  for (const curve of family) {
    for (let i = 0; i < z.length; i += 1, at += 1) {
      xs[at] = z[i];
      ys[at] = curve.v[i];
      ks[at] = curve.k;
    }
    xs[at] = null;
    ys[at] = null;
    ks[at] = null;
    at += 1;
  }
  const value = { xs, ys, ks };
  if (family.length) derived.set(family[0], { z, family, value });
  return value;
}

/**
 * Fig. 3: the family in grey (one trace, curves separated by gaps: one trace draws
 * faster than fifteen), the current k (the frame's last curve) highlighted.
 */
export function phaseFigure(frame, state) {
  const curves = frame.phase.curves;
  const z = frame.phase.z;
  const family = curves.slice(0, -1);
  const { xs, ys, ks } = familyTrace(z, family);
  const current = curves[curves.length - 1];
  const name = family.length
    ? `k = ${fmt(family[0].k)}, ${fmt(family[1]?.k)}, …, ${fmt(family[family.length - 1].k)}`
    : "family";
  const zv = (format) => hoverXY(state, ["z", "", ".3f"], ["ẋ", "m/s", format]);
  const data = [
    {
      type: "scatter", mode: "lines", name,
      x: xs, y: ys, customdata: ks, connectgaps: false,
      line: { color: PALETTE.phase.family, width: 1 },
      hovertemplate: `${hover("k", "customdata", ".4g", "N/s", state)}<br>${zv(".3g")}<extra></extra>`,
    },
    {
      type: "scatter", mode: "lines", name: `current k = ${fmt(current.k)}`,
      x: z, y: current.v,
      line: { color: PALETTE.phase.current, width: 3 },
      hovertemplate: `k = ${fmt(current.k)} ${unit("N/s", state)}<br>${zv(".4g")}<extra></extra>`,
    },
  ];
  const zStar = Number(state.z_ba);
  // the family's extent once per family, beside the current curve's
  const ends = [derivedOf(ys, () => extent(ys, true)), extent(current.v, true)]
    .filter(([low]) => low !== null);
  const lo = ends.length ? Math.min(...ends.map(([low]) => low)) : null;
  const hi = ends.length ? Math.max(...ends.map(([, high]) => high)) : null;
  // marker lines are traces, not layout shapes: a shape costs a separate drawing pass
  data.push({
    type: "scatter", mode: "lines", name: `z* = ${fmt(zStar)}`,
    x: [zStar, zStar], y: [lo, hi], hoverinfo: "skip",
    line: { color: PALETTE.phase.zStar, width: 1, dash: "dot" },
  });
  const layout = baseLayout("phase", state, {
    yaxis: { title: { text: `${plotAxes("phase", state).y} (log)`, standoff: 4 }, type: "log",
      exponentformat: "power" },
    // below the plot: inside, it covered the log axis and the family's slow end
    legend: { orientation: "h", x: 0, y: -0.2, yanchor: "top" },
    margin: { l: 58, r: 12, t: 8, b: 80 },
  });
  return { data, layout };
}

/** [min, max] of the finite values (positive ones only when `positive`). */
export function extent(values, positive = false) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const value of values) {
    if (value == null || !Number.isFinite(value) || (positive && value <= 0)) continue;
    if (value < lo) lo = value;
    if (value > hi) hi = value;
  }
  return lo <= hi ? [lo, hi] : [null, null];
}

/** Linear interpolation of (xs, ys) at x; null outside the grid. */
export function interpolate(xs, ys, x) {
  const n = xs.length;
  if (!n || x < xs[0] || x > xs[n - 1]) return null;
  let lo = 0;
  let hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] <= x) lo = mid; else hi = mid;
  }
  if (xs[hi] === xs[lo]) return ys[lo];
  const t = (x - xs[lo]) / (xs[hi] - xs[lo]);
  return ys[lo] + t * (ys[hi] - ys[lo]);
}

/** The band's shading: Okabe–Ito blue, faint enough that the curves read through it. */
export const BAND_FILL = "rgba(0, 114, 178, 0.13)";
/** The name of the shaded band of rates (models/sensitivity.js). */
export const BAND_NAME = "most sensitive to V, δ";

/**
 * Fig. 5: F_ba(k) for the four F̂ (the chosen one drawn heavier), the current k, and
 * the simulated break-away points of the ramp (E7) and of LuGre when present.
 * `sim` / `lugre`: {k, u_ba, F_ba, stale} or null. `band`: {k: [low, high]} the rates
 * where F_ba(k) is most sensitive to V and δ (rateBand), shaded where it meets the
 * plotted rates.
 */
export function breakawayFigure(frame, state, sim = null, lugre = null, band = null) {
  const ba = frame.breakaway;
  const kF = (force) => hoverXY(state, ["k", "N/s", ".3g"], [force, "N", ".4g"]);
  const data = ["Fc", "Fs", "avg", "self"].map((name) => ({
    type: "scatter", mode: "lines", name: F_HAT_LABEL[name],
    x: ba.k, y: ba[name],
    line: { color: COLORS[name], width: name === state.F_hat ? 3 : 1.3, dash: F_HAT_DASH[name] },
    hovertemplate: `${F_HAT_LABEL[name]}<br>${kF("F_ba")}<extra></extra>`,
  }));
  const k = Number(state.k);
  const yCurrent = interpolate(ba.k, ba[state.F_hat], k);
  data.push({
    type: "scatter", mode: "markers", name: `current k = ${fmt(k)}`,
    x: [k], y: [yCurrent],
    marker: { color: COLORS.current, size: 11, symbol: "circle", line: { color: "#fff", width: 1 } },
    hovertemplate: `current k<br>${kF("F_ba")}<extra></extra>`,
  });
  if (sim) {
    const opacity = sim.stale ? 0.35 : 1;
    data.push({
      type: "scatter", mode: "markers", name: "ramp sim.: u(t_ba)",
      x: sim.k, y: sim.u_ba, opacity,
      marker: { color: COLORS.simulation, size: 7, symbol: "circle" },
      hovertemplate: `ramp simulation<br>${kF("u(t_ba)")}<extra></extra>`,
    });
    data.push({
      type: "scatter", mode: "markers", name: "ramp sim.: F(t_ba)",
      x: sim.k, y: sim.F_ba, opacity,
      marker: { color: COLORS.simulation, size: 7, symbol: "circle-open" },
      hovertemplate: `ramp simulation<br>${kF("F(t_ba)")}<extra></extra>`,
    });
  }
  if (lugre) {
    data.push({
      type: "scatter", mode: "markers", name: "LuGre 1995: max F",
      x: lugre.k, y: lugre.F_ba, opacity: lugre.stale ? 0.35 : 1,
      marker: { color: COLORS.lugre, size: 8, symbol: "diamond" },
      hovertemplate: `LuGre 1995<br>${kF("max F")}<extra></extra>`,
    });
  }
  const [lo, hi] = extent(data.flatMap((trace) => trace.y));
  data.splice(4, 0, {
    type: "scatter", mode: "lines", name: "line at the current k", showlegend: false,
    x: [k, k], y: [lo, hi], hoverinfo: "skip",
    line: { color: COLORS.current, width: 1, dash: "dash" },
  });
  const [kLo, kHi] = [ba.k[0], ba.k[ba.k.length - 1]];
  if (band && band.k[1] > kLo && band.k[0] < kHi) {
    const left = Math.max(band.k[0], kLo);
    const right = Math.min(band.k[1], kHi);
    // a closed polygon under the curves' extent: the autorange stays the curves'
    data.push({
      type: "scatter", mode: "lines", name: BAND_NAME, fill: "toself", fillcolor: BAND_FILL,
      x: [left, right, right, left, left], y: [lo, lo, hi, hi, lo],
      line: { width: 0 }, hoverinfo: "skip",
    });
  }
  const layout = baseLayout("breakaway", state, {
    legend: { orientation: "h", x: 0, y: -0.2, yanchor: "top" },
    margin: { l: 58, r: 12, t: 8, b: 80 },
  });
  return { data, layout };
}

/** The figures of one redraw (all four, or those in `ids`), keyed by plot id. */
export function figures(frame, state, sim, lugre, ids = PLOT_IDS, band = null) {
  const build = {
    stribeck: () => stribeckFigure(frame, state),
    hysteresis: () => hysteresisFigure(frame, state),
    phase: () => phaseFigure(frame, state),
    breakaway: () => breakawayFigure(frame, state, sim, lugre, band),
  };
  return Object.fromEntries(ids.map((id) => [id, build[id]()]));
}

function fmt(value) {
  return Number.isFinite(value) ? String(Number(value.toPrecision(4))) : String(value);
}

/**
 * A figure styled for where it is shown: presentation mode (ticks and titles from 18 px,
 * lines and markers 1.7× heavier) and dark mode (transparent backgrounds, light text).
 */
export function styled(figure, { present = false, dark = false } = {}) {
  if (!present && !dark) return figure;
  const layout = { ...figure.layout };
  const ink = dark ? "#e4e7eb" : undefined;
  const grid = dark ? "#3a414b" : undefined;
  layout.font = { ...(layout.font ?? {}), ...(present ? { size: 18 } : {}), ...(ink ? { color: ink } : {}) };
  if (dark) {
    layout.paper_bgcolor = "rgba(0,0,0,0)";
    layout.plot_bgcolor = "rgba(0,0,0,0)";
    if (layout.legend) layout.legend = { ...layout.legend, bgcolor: "rgba(30,34,40,0.8)" };
  }
  for (const axis of ["xaxis", "yaxis", "yaxis2"]) {
    if (!layout[axis]) continue;
    layout[axis] = {
      ...layout[axis],
      ...(present ? { tickfont: { size: 18 } } : {}),
      ...(grid ? { gridcolor: grid, zerolinecolor: "#6b7380", linecolor: "#6b7380" } : {}),
    };
  }
  if (present) {
    // room for the larger ticks (half the last x label reaches past the axis end), and
    // for a legend below the plot in its larger type
    const bottom = Math.max(60, (layout.margin?.b ?? 42) + 24);
    layout.margin = { ...(layout.margin ?? {}), l: 78, b: bottom, r: layout.yaxis2 ? 96 : 28 };
  }
  let data = present ? figure.data.map((trace) => ({
    ...trace,
    ...(trace.line ? { line: { ...trace.line, width: (trace.line.width ?? 1.5) * 1.7 } } : {}),
    ...(trace.marker && typeof trace.marker.size === "number"
      ? { marker: { ...trace.marker, size: trace.marker.size * 1.4 } } : {}),
  })) : figure.data;
  if (dark) data = data.map(onDark);
  return { data, layout };
}

function onDark(trace) {
  const out = { ...trace };
  if (trace.line && DARK_INK[trace.line.color]) {
    out.line = { ...trace.line, color: DARK_INK[trace.line.color] };
  }
  if (trace.marker && typeof trace.marker.color === "string" && DARK_INK[trace.marker.color]) {
    out.marker = { ...trace.marker, color: DARK_INK[trace.marker.color] };
  }
  return out;
}
