// The axes of a live drawing (livedraw.js) on a Plotly graph: Plotly's plot area and
// ranges (a person's zoom kept, otherwise Plotly's autorange, axes.js), the pixel map
// of each axis, and its ticks when the static layer needs them.

import { autorange, ticks } from "./axes.js";
import { AXIS_KEY } from "./draw.js";

/** The axis attributes a live drawing reads (the figure's over Plotly's full axis, which
 *  holds hundreds: copying it whole cost a frame a millisecond under a phone's CPU). */
const AXIS_STYLE = ["exponentformat", "gridcolor", "gridwidth", "overlaying", "showgrid", "side",
  "tickfont", "tickmode", "zeroline", "zerolinecolor", "zerolinewidth"];

function axisStyle(full, own) {
  const style = {};
  for (const name of AXIS_STYLE) style[name] = own[name] ?? full[name];
  return style;
}

/** The traces of `figure` that graph `gd` shows (those hidden from its legend are not). */
export function shownTraces(gd, figure) {
  const shown = gd.data ?? [];
  return figure.data.filter((trace, i) => (shown[i]?.visible ?? true) === true);
}

/** The axes of a figure drawn on graph `gd`: range, ticks and pixel map per axis key. */
export function axesOf(gd, figure, traces) {
  const full = gd._fullLayout;
  const size = full._size;
  const out = {};
  for (const key of Object.keys(figure.layout)) {
    if (!AXIS_KEY.test(key) || !full[key]) continue;
    const letter = key[0];
    const id = letter + key.slice(5); // "x", "y", "y2"
    const log = (figure.layout[key].type ?? full[key].type) === "log";
    const length = letter === "x" ? size.w : size.h;
    // a range the person chose (zoom, pan) is kept; otherwise Plotly's autorange
    const range = full[key].autorange === false
      ? full[key].range.slice()
      : autorange(traces, letter, {
        length, log, onAxis: (trace) => (trace[`${letter}axis`] ?? letter) === id,
      });
    const [r0, r1] = range;
    const toPixel = letter === "x"
      ? (l) => size.l + ((l - r0) / (r1 - r0)) * size.w
      : (l) => size.t + size.h - ((l - r0) / (r1 - r0)) * size.h;
    // the same map as pixel = offset + scale·value, which a line's thousands of points
    // take without a call each (drawTrace)
    const scale = letter === "x" ? size.w / (r1 - r0) : -size.h / (r1 - r0);
    const offset = letter === "x" ? size.l - r0 * scale : size.t + size.h - r0 * scale;
    out[id] = {
      key, letter, log, range, toPixel, scale, offset,
      // on a log axis a line runs to a non-positive value far below the range (Plotly's
      // LOG_CLIP); a marker there is not drawn
      map: log ? (v, line = false) => {
        if (v > 0) return toPixel(Math.log10(v));
        return line ? toPixel(0.5 * (r0 + r1 - 20 * Math.abs(r0 - r1))) : NaN;
      } : toPixel,
      length,
      style: axisStyle(full[key], figure.layout[key]),
    };
  }
  return out;
}

/** The ticks of every axis of `axes` (axesOf) set on it: only the static layer and the
 *  tests read them. */
export function addTicks(out) {
  // an axis laid over another takes its ticks where the other's are (tickmode "sync")
  for (const axis of Object.values(out)) {
    const under = axis.style.overlaying && out[axis.style.overlaying];
    axis.ticks = ticks(axis.range, {
      letter: axis.letter, length: axis.length, log: axis.log,
      exponentformat: axis.style.exponentformat,
      sync: under && (axis.style.tickmode ?? "sync") === "sync"
        ? { range: under.range, ticks: ticks(under.range, { letter: under.letter, length: under.length, log: under.log, exponentformat: under.style.exponentformat }) }
        : null,
    });
  }
  return out;
}

/** The ranges and tick labels a live drawing of `figure` on `gd` uses (for tests). */
export function liveAxes(gd, figure) {
  const axes = addTicks(axesOf(gd, figure, shownTraces(gd, figure)));
  return Object.fromEntries(Object.entries(axes).map(([id, axis]) => [id, {
    range: axis.range, ticks: axis.ticks.map((tick) => [tick.value, tick.text]),
  }]));
}
