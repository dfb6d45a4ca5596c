// Pure functions from a finished fit job (its `series` and `report`) to fresh Plotly
// figures {data, layout} for the data panel, and the number formats of its tables.
// Nothing here touches the DOM; datapanel.js hands the figures to Plotly.react.

import { PALETTE } from "../plots/palette.js";

/** Axis title of each column a series can hold. */
export const AXIS_TITLES = {
  t: "t [s]",
  x: "x [m]",
  v: "v [m/s]",
  a: "a [m/s²]",
  k: "k [N/s]",
  direction: "direction [±1]",
  dwell: "dwell [s]",
};

/** How each report parameter is shown: symbol and unit. */
export const PARAM_LABELS = {
  Fc: "Fc [N]",
  Fs: "Fs [N]",
  V: "V [m/s]",
  delta: "δ",
  s: "s [1/m]",
  sigma: "σ [N·s/m]",
  Fc_neg: "Fc⁻ [N]",
  Fs_neg: "Fs⁻ [N]",
  F_offset: "F0 [N]",
  alpha: "α [1/s]",
  m_e: "m_e [kg]",
  A: "A [N]",
  wavelength: "λ [m]",
  phase: "φ [rad]",
  tau: "τ [s]",
  play: "b [m]",
  zeta: "ζ",
  tau_d: "τ_d [s]",
};

const COLORS = { ...PALETTE.fitModel, ...PALETTE.fitResidual };

/**
 * A number to `digits` significant digits, trailing zeros kept (15.00, 0.04427, 2961);
 * exponent form below 1e-3 and from 1e6 on (2.6e-4).
 */
export function formatNumber(value, digits = 4) {
  if (value === null || value === undefined) return "–";
  if (!Number.isFinite(value)) return String(value);
  if (value === 0) return "0";
  const magnitude = Math.abs(value);
  if (magnitude < 1e-3 || magnitude >= 1e6) {
    const [mantissa, exponent] = value.toExponential(digits - 1).split("e");
    return `${mantissa}e${Number(exponent)}`;
  }
  const decimals = Math.max(0, digits - 1 - Math.floor(Math.log10(magnitude)));
  return value.toFixed(decimals);
}

/** Label of a report parameter: its symbol and unit, and the report key when it differs. */
export function paramLabel(name) {
  const label = PARAM_LABELS[name];
  if (!label) return name;
  return label === name || label.startsWith(`${name} `) ? label : `${label} (${name})`;
}

/** "value ± stderr", or "value (± not determined)" when the data do not fix it. */
export function formatWithError(value, stderr) {
  const shown = formatNumber(value, 4);
  if (stderr === null || stderr === undefined || !Number.isFinite(stderr)) {
    return `${shown} ± not determined`;
  }
  return `${shown} ± ${formatNumber(stderr, 2)}`;
}

function forceTitle(kind) {
  return kind === "breakaway" ? "F_ba [N]" : "F [N]";
}

function layout(revision, xTitle, yTitle, extra = {}) {
  return {
    uirevision: revision, // a new fit resets the zoom; redraws of the same fit keep it
    margin: { l: 60, r: 12, t: 8, b: 78 },
    font: { size: 11 },
    hovermode: "closest",
    showlegend: true,
    // below the axes: the toolbar appears at the top right, and the data fill the plot
    legend: { orientation: "h", x: 0, y: -0.2, yanchor: "top" },
    xaxis: { title: { text: xTitle, standoff: 4 }, zeroline: false, exponentformat: "power" },
    yaxis: { title: { text: yTitle, standoff: 4 }, zeroline: true, exponentformat: "power" },
    ...extra,
  };
}

function column(series, name) {
  return Array.from(series.columns[name] ?? []);
}

/** The three traces of measured force and the two models over `x`: `mode` "lines" or
 *  "markers" for the measured points, `models` for the models. */
function forceTraces(series, x, mode, models) {
  return [
    {
      type: "scatter", mode, name: "measured",
      x, y: column(series, "measured"),
      line: { color: COLORS.measured, width: 1 },
      marker: { color: COLORS.measured, size: 5 },
    },
    {
      type: "scatter", mode: models, name: "base model",
      x: x.slice(), y: column(series, "base"),
      line: { color: COLORS.base, width: 1.4, dash: "dash" },
      marker: { color: COLORS.base, size: 6, symbol: "circle-open" },
    },
    {
      type: "scatter", mode: models, name: "final model",
      x: x.slice(), y: column(series, "final"),
      line: { color: COLORS.final, width: 1.6 },
      marker: { color: COLORS.final, size: 6, symbol: "x-thin-open" },
    },
  ];
}

/**
 * Measured force with the base and the final model: against x for a time series (the
 * measured and fitted hysteresis, drawn as lines in the record's order), against v for
 * steady data, against k for break-away data (as points).
 */
export function modelFigure(series, kind, revision) {
  if (kind === "timeseries") {
    return { data: forceTraces(series, column(series, "x"), "lines", "lines"),
      layout: layout(revision, AXIS_TITLES.x, forceTitle(kind)) };
  }
  const x = column(series, series.axis);
  const data = forceTraces(series, x, "markers", kind === "steady" ? "lines" : "markers");
  return { data, layout: layout(revision, AXIS_TITLES[series.axis] ?? series.axis, forceTitle(kind)) };
}

/** Direction changes of x a time window shows: three full cycles. */
const WINDOW_REVERSALS = 6;
/** A turn counts once x has come back this share of its whole range (a measured x
 *  jitters: its small wiggles are no cycles). */
const TURN_SHARE = 0.05;

/** [t0, t1]: the start of a time series over its first WINDOW_REVERSALS reversals of x
 *  (at least a hundredth of the record; all of it when it turns fewer times). */
export function timeWindow(t, x) {
  const end = t[t.length - 1];
  const [lo, hi] = [Math.min(...x), Math.max(...x)];
  const turn = TURN_SHARE * (hi - lo);
  // taken as rising at first: a record that starts falling "turns" from its first
  // sample, which is no reversal
  let turns = 0;
  let rising = true;
  let extreme = x[0];
  for (let i = 1; i < x.length; i += 1) {
    if (rising ? x[i] > extreme : x[i] < extreme) extreme = x[i];
    if ((rising ? extreme - x[i] : x[i] - extreme) < turn) continue;
    // x has turned: from a maximum when it rose, from a minimum when it fell
    if (!(rising && extreme === x[0])) turns += 1;
    if (turns >= WINDOW_REVERSALS) return [t[0], Math.max(t[i], t[0] + 0.01 * (end - t[0]))];
    rising = !rising;
    extreme = x[i];
  }
  return [t[0], end];
}

/** Measured and fitted force over time, a time series only: a window of a few cycles
 *  to read them by, zoomable, with the whole record in a range slider under it. */
export function timeFigure(series, revision) {
  const t = column(series, "t");
  const data = forceTraces(series, t, "lines", "lines");
  const figure = { data, layout: layout(revision, AXIS_TITLES.t, forceTitle("timeseries")) };
  const range = timeWindow(t, column(series, "x"));
  Object.assign(figure.layout.xaxis, { range, autorange: false, rangeslider: { visible: true, thickness: 0.12 } });
  // the legend under the range slider
  figure.layout.legend = { ...figure.layout.legend, y: -0.45 };
  figure.layout.margin = { ...figure.layout.margin, b: 110 };
  return figure;
}

function residualTraces(series, x, dense) {
  return [
    {
      type: "scatter", mode: dense ? "lines" : "markers", name: "before (base model)",
      x, y: column(series, "residual_before"),
      line: { color: COLORS.before, width: 1 },
      marker: { color: COLORS.before, size: 4 },
    },
    {
      type: "scatter", mode: dense ? "lines" : "markers", name: "after (final model)",
      x: x.slice(), y: column(series, "residual_after"),
      line: { color: COLORS.after, width: 1 },
      marker: { color: COLORS.after, size: 4 },
    },
  ];
}

/** The caption of the model figure, matching how each kind is drawn. */
export function modelCaption(kind) {
  if (kind === "timeseries") {
    return "F against x, the measured and fitted hysteresis: measured (grey line), base model "
      + "(red, dashed), final model with the accepted effects (blue)";
  }
  const models = kind === "steady"
    ? "base model (red, dashed line), final model with the accepted effects (blue line)"
    : "base model (red open circles), final model with the accepted effects (blue crosses)";
  return `measured (grey dots), ${models}`;
}

/** Residual (measured − model) before and after against the main axis. */
export function residualFigure(series, kind, revision) {
  const x = column(series, series.axis);
  return {
    data: residualTraces(series, x, kind === "timeseries"),
    layout: layout(revision, AXIS_TITLES[series.axis] ?? series.axis, "residual [N]"),
  };
}

/** Residual before and after against the regressor that showed `effect`'s signature. */
export function effectFigure(series, kind, effect, revision) {
  const regressor = series.effect_regressor[effect];
  const x = column(series, regressor);
  const figure = {
    data: residualTraces(series, x, false),
    layout: layout(revision, AXIS_TITLES[regressor] ?? regressor, "residual [N]"),
  };
  // dwell acts through ln(1 + dwell/τ_d): its signature reads best on a log axis
  if (regressor === "dwell" && x.length && x.every((value) => value > 0)) {
    // one labelled tick per decade, as plain numbers (0.2, 2, 20 s), not 2/5 minor labels
    Object.assign(figure.layout.xaxis, { type: "log", dtick: 1, tickformat: "~g" });
  }
  return figure;
}

/** An axis title "name [unit]" in the data's units (rotary data: N·m, rad, rad/s). */
export function inUnits(title, units, forceUnit) {
  const match = /^(.*) \[(.*)\]$/.exec(title ?? "");
  if (!match || !units) return title;
  const [, name, unit] = match;
  const key = name === "residual" || name === "F_ba" || name === "F" ? null : name;
  const wanted = key ? units[key] : (unit === "N" ? forceUnit : null);
  return wanted ? `${name} [${wanted}]` : title;
}

/** "name = %{x:.4g} unit" for a hover label, from an axis title "name [unit]". */
function hoverPart(title, variable) {
  const match = /^(.*) \[(.*)\]$/.exec(title ?? "");
  const [name, unit] = match ? [match[1], match[2]] : [title ?? variable, ""];
  const shown = unit === "-" || unit === "±1" ? "" : ` ${unit}`;
  return `${name} = %{${variable}:.4g}${shown}`;
}

/** The axis titles in the data's units, and every trace's hover label in them too. */
function relabel(figure, units, forceUnit) {
  for (const axis of ["xaxis", "yaxis"]) {
    const title = figure.layout[axis]?.title;
    if (title && typeof title.text === "string") title.text = inUnits(title.text, units, forceUnit);
  }
  const x = hoverPart(figure.layout.xaxis?.title?.text, "x");
  const y = hoverPart(figure.layout.yaxis?.title?.text, "y");
  for (const trace of figure.data) {
    trace.hovertemplate = `${trace.name}<br>${x}<br>${y}<extra></extra>`;
  }
  return figure;
}

/** Every figure of one finished fit: {model, time (a time series' force over time, else
 *  null), residual, effects: [{effect, regressor, figure}]}. */
export function fitFigures(job) {
  const { series, report } = job;
  const kind = report.kind;
  const units = report.units;
  const forceUnit = units?.[kind === "breakaway" ? "F_ba" : "F"] ?? "N";
  return {
    model: relabel(modelFigure(series, kind, job.id), units, forceUnit),
    time: kind === "timeseries" ? relabel(timeFigure(series, job.id), units, forceUnit) : null,
    residual: relabel(residualFigure(series, kind, job.id), units, forceUnit),
    effects: report.effects.filter((effect) => effect in series.effect_regressor).map((effect) => ({
      effect,
      regressor: series.effect_regressor[effect],
      figure: relabel(effectFigure(series, kind, effect, job.id), units, forceUnit),
    })),
  };
}
