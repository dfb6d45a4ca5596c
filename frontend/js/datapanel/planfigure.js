// Pure functions from a plan (POST /api/plan's answer) and its report to the data
// panel's words and figure: the design in one sentence, and each parameter's standard
// error relative to its value, now and after the plan. Nothing here touches the DOM.

import { PALETTE } from "../plots/palette.js";
import { formatNumber } from "./fitplots.js";

const SYMBOLS = { delta: "δ", sigma: "σ" };
const COLORS = PALETTE.plan;
/** Where a parameter the data give no standard error is marked [%]. */
const NONE_AT = 1e4;
/** Now and after are drawn this far left and right of their parameter, side by side. */
const OFFSET = 0.14;

export const symbol = (name) => SYMBOLS[name] ?? name;

/** The parameters a report does not determine (what a plan is for). */
export function undetermined(report) {
  return Object.entries(report.final?.determined ?? {}).filter(([, ok]) => !ok).map(([name]) => name);
}

/** The report as the plan needs it: its parameters, their covariance, noise, units and
 *  extent (the residual series and the diagnosis stay behind). */
export function planReport(report) {
  const keep = ["kind", "n", "noise_floor", "residual_white", "effects", "units", "extent", "s"];
  const out = Object.fromEntries(keep.filter((key) => key in report).map((key) => [key, report[key]]));
  const { params, stderr, determined, rmse, covariance } = report.final;
  out.final = { params, stderr, determined, rmse, ...(covariance ? { covariance } : {}) };
  return out;
}

function listed(values, unit) {
  const counts = new Map();
  for (const value of values) counts.set(value, (counts.get(value) ?? 0) + 1);
  return [...counts].map(([value, n]) => formatNumber(value, 3) + (n > 1 ? ` (×${n})` : ""))
    .join(", ") + ` ${unit}`;
}

/** The design in one sentence, in the record's units. */
export function designSentence(plan) {
  const design = plan.design;
  const u = plan.units;
  const targets = plan.targets.map(symbol).join(", ");
  if (!design) return "No runs proposed: see the notes.";
  if (design.family === "ramps") {
    return `${design.runs} force ramps from rest, at k = ${listed(design.rates, u.k)}, each up `
      + `to at most ${formatNumber(Math.max(...design.end_force), 3)} ${u.F}: to determine ${targets}.`;
  }
  if (design.family === "steady") {
    return `${design.runs} speed set-points, each at +v and −v, v = ${listed(design.speeds, u.v)}: `
      + `to determine ${targets}.`;
  }
  return `One position sine of amplitude ${formatNumber(design.amplitude, 3)} ${u.x} at `
    + `${formatNumber(design.frequency, 3)} Hz for ${formatNumber(design.duration, 3)} s `
    + `(peak speed ${formatNumber(design.peak_speed, 3)} ${u.v}, peak force `
    + `${formatNumber(design.peak_force, 3)} ${u.F}): to determine ${targets}.`;
}

const relative = (stderr, value) => (stderr == null || !value ? null : (100 * stderr) / Math.abs(value));

/**
 * The figure: relative standard error [%] per parameter (log axis), now and after the
 * plan, with the values across an open range as small dots and the bar of §8 (a
 * relative standard error of 100 %) dashed.
 */
export function planFigure(plan, report) {
  const names = Object.keys(plan.predicted);
  const labels = names.map(symbol);
  const params = report.final.params;
  const now = names.map((name) => relative(plan.predicted[name].stderr_now, params[name]));
  const at = (shift) => names.map((_, i) => i + shift);
  const across = { x: [], y: [] };
  const after = names.map((name, i) => {
    const entry = plan.predicted[name];
    const points = entry.across ?? [];
    for (const point of points) {
      const y = relative(point.stderr_after, point.value);
      if (y != null) {
        across.x.push(i + OFFSET);
        across.y.push(y);
      }
    }
    // an open parameter's middle value is the middle of the values across its range
    const middle = points.length ? points[(points.length - 1) >> 1].value : params[name];
    return relative(entry.stderr_after, middle);
  });
  const data = [
    {
      type: "scatter", mode: "markers", name: "now", x: at(-OFFSET), y: now, text: labels,
      marker: { color: COLORS.now, size: 11, symbol: "circle" },
      hovertemplate: "%{text} now: %{y:.3g} %<extra></extra>",
    },
    {
      type: "scatter", mode: "markers", name: "now: no standard error", showlegend: false,
      x: at(-OFFSET).filter((_, i) => now[i] == null), y: now.filter((v) => v == null).map(() => NONE_AT),
      text: labels.filter((_, i) => now[i] == null),
      marker: { color: COLORS.now, size: 11, symbol: "triangle-up" },
      hovertemplate: "%{text}: the data give no standard error<extra></extra>",
    },
    {
      type: "scatter", mode: "markers", name: "after the plan", x: at(OFFSET), y: after, text: labels,
      marker: { color: COLORS.after, size: 12, symbol: "diamond" },
      hovertemplate: "%{text} after: %{y:.3g} %<extra></extra>",
    },
    {
      type: "scatter", mode: "markers", name: "across the open range", x: across.x, y: across.y,
      marker: { color: COLORS.after, size: 5, symbol: "circle-open" },
      hovertemplate: "after, across its range: %{y:.3g} %<extra></extra>",
    },
    {
      type: "scatter", mode: "lines", name: "determined below", showlegend: false,
      x: [-0.5, names.length - 0.5],
      y: [100, 100], line: { color: COLORS.bar, width: 1, dash: "dash" }, hoverinfo: "skip",
    },
  ];
  const layout = {
    uirevision: "plan",
    margin: { l: 64, r: 12, t: 8, b: 70 },
    font: { size: 11 },
    showlegend: true,
    legend: { orientation: "h", x: 0, y: -0.2, yanchor: "top" },
    xaxis: { title: { text: "parameter", standoff: 4 }, tickvals: at(0), ticktext: labels,
      range: [-0.5, names.length - 0.5], zeroline: false, showgrid: false },
    yaxis: { type: "log", title: { text: "standard error [% of value]", standoff: 4 },
      exponentformat: "power" },
  };
  return { data, layout };
}
