// A figure drawn on a canvas inside a Plotly graph, for the frames of a moving hand:
// Plotly needs 13–24 ms to redraw one of these plots (benchmarks/ui_latency.py), this
// 0.2–2 ms. The canvas lies between Plotly's two SVG layers, in the graph's own plot area
// (Plotly's last layout: size and margins, which a legend may have widened): under it
// the paper, over it the legend and the axis titles, whose names are brought up to date.
// Backgrounds, grid, zero lines, traces and tick labels are drawn as Plotly draws them,
// with Plotly's own ranges and ticks (axes.js), while Plotly's layers for them are hidden.
// A person's zoom is kept, and traces hidden from the legend stay hidden.

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

const legendNames = new WeakMap(); // graph -> the names a live frame last gave its legend

/** Plotly's layers that the canvas stands in for, in the graph's first SVG. */
const COVERED = [".bglayer", ".layer-below", ".cartesianlayer"];
const DASHES = { dash: 3, dot: 1, longdash: 5 };

/** Graph -> its Plotly container, first SVG, live canvas and that canvas's context,
 *  found once (each frame asked the DOM five times a plot), found again when Plotly has
 *  replaced them. */
const found = new WeakMap();

function layers(gd) {
  const known = found.get(gd);
  if (known?.main.isConnected && known.main.parentNode === known.container && gd.contains(known.container)) {
    return known;
  }
  const container = gd.querySelector(".svg-container");
  const main = container?.querySelector("svg.main-svg");
  const entry = { container, main, canvas: container?.querySelector("canvas.live-layer") ?? null, ctx: null };
  if (main) found.set(gd, entry);
  return entry;
}

/** The live canvas's context, desynchronized from the page's frames: a canvas drawn at
 *  every frame cost the main thread's commit 0.5 ms a plot at the machine's speed (its
 *  pixels handed to the compositor with the page's frame), 2.3 of 8.5 ms a frame of a
 *  drag; desynchronized, its pixels go to the screen apart from the page's commit
 *  (0.45 ms for all four plots). The browser may show them a frame sooner than the
 *  page's other changes (the legend's names), which a moving hand does not see. */
const CONTEXT = { desynchronized: true };

function canvasOf(gd) {
  const entry = layers(gd);
  if (!entry.canvas || entry.canvas.parentNode !== entry.container) {
    entry.canvas = document.createElement("canvas");
    entry.canvas.className = "live-layer";
    entry.canvas.setAttribute("aria-hidden", "true");
    entry.main.after(entry.canvas);
    entry.ctx = null;
  }
  entry.ctx ??= entry.canvas.getContext("2d", CONTEXT);
  return entry;
}

function cover(gd, hidden) {
  const { main } = layers(gd);
  for (const selector of COVERED) {
    const layer = main?.querySelector(`:scope > ${selector}`);
    if (layer) layer.style.visibility = hidden ? "hidden" : "";
  }
}

/** True while graph `gd` shows the canvas instead of Plotly's drawing. */
export function isLive(gd) {
  return gd.dataset.live === "true";
}

/** Plotly's drawing shown again (once Plotly has drawn the figure the canvas showed). */
export function clearLive(gd) {
  if (!isLive(gd)) return;
  gd.dataset.live = "false";
  legendNames.delete(gd); // Plotly's legend holds its own names again
  const { canvas } = layers(gd);
  if (canvas) canvas.style.display = "none";
  cover(gd, false);
}

/** The axes of a figure drawn on graph `gd`: range, ticks and pixel map per axis key. */
function axesOf(gd, figure, traces) {
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
    out[id] = {
      key, letter, log, range, toPixel,
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
function addTicks(out) {
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

/** The canvas's font, set only when it changes: each assignment parses the font anew
 *  and brings the page's styles up to date. */
function setFont(ctx, size, family) {
  const font = `${size}px ${family}`;
  if (ctx.lastFont !== font) {
    ctx.font = font;
    ctx.lastFont = font;
  }
}

/** Widths of texts [px] by font and text: the tick labels of one frame are mostly those
 *  of the one before. */
const widths = new Map();
const WIDTHS_KEPT = 2000;

function textWidth(ctx, text, size, family) {
  const key = `${size}px ${family}\u0000${text}`;
  let width = widths.get(key);
  if (width === undefined) {
    setFont(ctx, size, family);
    width = ctx.measureText(text).width;
    if (widths.size >= WIDTHS_KEPT) widths.clear();
    widths.set(key, width);
  }
  return width;
}

/** Tick labels [{text, x, y, align, size, family, color}], Plotly's <sup> powers raised
 *  at 70 %: the bases first, then the powers, so that the font changes once or twice a
 *  plot rather than twice a label. */
function drawTickLabels(ctx, labels) {
  const parts = [];
  for (const label of labels) {
    const match = /^(.*?)<sup>(.*)<\/sup>$/.exec(label.text);
    const base = match ? match[1] : label.text;
    const sup = match ? match[2] : "";
    const supSize = label.size * 0.7;
    const baseWidth = textWidth(ctx, base, label.size, label.family);
    const width = baseWidth + (sup ? textWidth(ctx, sup, supSize, label.family) : 0);
    const left = label.align === "end" ? label.x - width : label.align === "middle" ? label.x - width / 2 : label.x;
    parts.push({ text: base, x: left, y: label.y, size: label.size, family: label.family, color: label.color });
    if (sup) {
      parts.push({ text: sup, x: left + baseWidth, y: label.y - 0.6 * supSize, size: supSize,
        family: label.family, color: label.color });
    }
  }
  parts.sort((a, b) => a.size - b.size);
  ctx.textAlign = "left";
  let color = null;
  for (const part of parts) {
    setFont(ctx, part.size, part.family);
    if (part.color !== color) {
      color = part.color;
      ctx.fillStyle = color;
    }
    ctx.fillText(part.text, part.x, part.y);
  }
}

function drawGrid(ctx, axes, size) {
  for (const axis of Object.values(axes)) {
    const { style, letter } = axis;
    const zero = !axis.log && style.zeroline !== false && axis.range[0] * axis.range[1] <= 0;
    ctx.setLineDash([]);
    if (style.showgrid !== false) {
      ctx.strokeStyle = style.gridcolor ?? "#eee";
      ctx.lineWidth = style.gridwidth ?? 1;
      ctx.beginPath();
      for (const tick of axis.ticks) {
        if (zero && tick.value === 0) continue;
        const p = Math.round(axis.toPixel(tick.value)) + 0.5;
        if (letter === "x") { ctx.moveTo(p, size.t); ctx.lineTo(p, size.t + size.h); } else { ctx.moveTo(size.l, p); ctx.lineTo(size.l + size.w, p); }
      }
      ctx.stroke();
    }
    if (zero) {
      const p = Math.round(axis.toPixel(0)) + 0.5;
      ctx.strokeStyle = style.zerolinecolor ?? "#444";
      ctx.lineWidth = style.zerolinewidth ?? 1;
      ctx.beginPath();
      if (letter === "x") { ctx.moveTo(p, size.t); ctx.lineTo(p, size.t + size.h); } else { ctx.moveTo(size.l, p); ctx.lineTo(size.l + size.w, p); }
      ctx.stroke();
    }
  }
}

function drawLabels(ctx, axes, size, font) {
  const labels = [];
  for (const axis of Object.values(axes)) {
    const tickfont = axis.style.tickfont ?? {};
    const fontSize = tickfont.size ?? font.size ?? 12;
    const family = tickfont.family ?? font.family;
    const color = tickfont.color ?? font.color ?? "#444";
    const [lo, hi] = axis.range;
    for (const tick of axis.ticks) {
      if (tick.value < Math.min(lo, hi) - 1e-9 * Math.abs(hi - lo)
          || tick.value > Math.max(lo, hi) + 1e-9 * Math.abs(hi - lo)) continue;
      const labelSize = fontSize * tick.scale;
      const p = axis.toPixel(tick.value);
      const label = { text: tick.text, size: labelSize, family, color };
      if (axis.letter === "x") {
        labels.push({ ...label, x: p, y: size.t + size.h + 0.5 + labelSize, align: "middle" });
      } else if (axis.style.side === "right") {
        labels.push({ ...label, x: size.l + size.w + 1, y: p + 0.35 * labelSize, align: "start" });
      } else {
        labels.push({ ...label, x: size.l - 1, y: p + 0.35 * labelSize, align: "end" });
      }
    }
  }
  drawTickLabels(ctx, labels);
}

/** Plotly's marker shapes (plotly.js symbol_defs) at radius r around (x, y). */
function markerPath(ctx, symbol, x, y, r) {
  const name = String(symbol ?? "circle").replace(/-open$/, "");
  if (name === "triangle-right" || name === "triangle-left") {
    const rt = (r * 2) / Math.sqrt(3);
    const sign = name === "triangle-right" ? 1 : -1;
    ctx.moveTo(x - (sign * r) / 2, y - rt);
    ctx.lineTo(x + sign * rt, y);
    ctx.lineTo(x - (sign * r) / 2, y + rt);
    ctx.closePath();
  } else if (name === "diamond") {
    const rd = r * 1.3;
    ctx.moveTo(x + rd, y);
    ctx.lineTo(x, y + rd);
    ctx.lineTo(x - rd, y);
    ctx.lineTo(x, y - rd);
    ctx.closePath();
  } else if (name === "x") {
    const rx = (r * 0.8) / Math.sqrt(2) + r * 0.4;
    ctx.moveTo(x - rx, y - rx);
    ctx.lineTo(x + rx, y + rx);
    ctx.moveTo(x + rx, y - rx);
    ctx.lineTo(x - rx, y + rx);
  } else {
    ctx.moveTo(x + r, y);
    ctx.arc(x, y, r, 0, 2 * Math.PI);
  }
}

/** Plotly's tolerance of a simplified line at pixel (x, y): `base` on the plot area,
 *  growing off it (plotly.js scatter/line_points.js, toleranceGrowth 10). */
function toleranceAt(x, y, base, size) {
  const xFrac = (x - size.l) / size.w;
  const yFrac = (y - size.t) / size.h;
  const off = Math.max(0, -xFrac, xFrac - 1) + Math.max(0, -yFrac, yFrac - 1);
  return (1 + 10 * off) * base;
}

/** Point `i` added to the path unless it is the last one added or the cluster's start;
 *  the last point added. */
function addPoint(ctx, px, py, i, drawn, first) {
  if (i === drawn || i === first) return drawn;
  ctx.lineTo(px[i], py[i]);
  return i;
}

/**
 * The points [start, end) of a line (pixels in `px`, `py`, all drawable) added to the
 * path, simplified as Plotly simplifies its lines (plotly.js scatter/line_points.js):
 * points that stay within the tolerance of one straight line collapse onto it, which
 * keeps its ends and its farthest points either way along it. A curve of a thousand
 * points becomes the few dozen segments Plotly draws, and a phone's processor strokes
 * those rather than the thousand.
 */
function strokeRun(ctx, px, py, start, end, base, size) {
  let first = start; // the cluster's start, drawn
  ctx.moveTo(px[first], py[first]);
  let drawn = first; // the last point added to the path
  let i = first + 1;
  while (i < end) {
    const x0 = px[first];
    const y0 = py[first];
    let high = i;
    const reach = Math.sqrt((px[high] - x0) ** 2 + (py[high] - y0) ** 2);
    if (reach < toleranceAt(px[high], py[high], base, size)) {
      i += 1;
      continue;
    }
    const ux = (px[high] - x0) / reach;
    const uy = (py[high] - y0) / reach;
    let low = first;
    let highVal = reach;
    let lowVal = 0;
    let minDev = 0;
    let maxDev = 0;
    let highFirst = false;
    let last = high; // the cluster's end
    let out = -1; // the first point off the cluster's line
    for (i += 1; i < end; i += 1) {
      const vx = px[i] - x0;
      const vy = py[i] - y0;
      const deviation = vx * uy - vy * ux;
      minDev = Math.min(minDev, deviation);
      maxDev = Math.max(maxDev, deviation);
      if (maxDev - minDev > toleranceAt(px[i], py[i], base, size)) {
        out = i;
        break;
      }
      last = i;
      const along = vx * ux + vy * uy;
      if (along > highVal) {
        highVal = along;
        high = i;
        highFirst = false;
      } else if (along < lowVal) {
        lowVal = along;
        low = i;
        highFirst = true;
      }
    }
    drawn = addPoint(ctx, px, py, highFirst ? high : low, drawn, first);
    drawn = addPoint(ctx, px, py, highFirst ? low : high, drawn, first);
    drawn = addPoint(ctx, px, py, last, drawn, first);
    if (out < 0) break;
    ctx.lineTo(px[out], py[out]);
    first = out;
    drawn = out;
    i = out + 1;
  }
  // points too close to the cluster's start to give it a direction end the run
  if (drawn !== end - 1 && end - 1 !== first) ctx.lineTo(px[end - 1], py[end - 1]);
}

function drawTrace(ctx, trace, axes, font, size) {
  const xAxis = axes[trace.xaxis ?? "x"];
  const yAxis = axes[trace.yaxis ?? "y"];
  if (!xAxis || !yAxis) return;
  const mode = trace.mode ?? "lines";
  const xs = trace.x ?? [];
  const ys = trace.y ?? [];
  ctx.globalAlpha = trace.opacity ?? 1;
  if (trace.fill === "toself" && trace.fillcolor) {
    // a shaded region (the break-away plot's band of rates), as Plotly fills it
    ctx.beginPath();
    for (let i = 0; i < xs.length; i += 1) {
      const px = xAxis.map(xs[i], true);
      const py = yAxis.map(ys[i], true);
      if (i === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
    }
    ctx.closePath();
    ctx.fillStyle = trace.fillcolor;
    ctx.fill();
  }
  if (mode.includes("lines") && (trace.line?.width ?? 2) > 0) {
    const line = trace.line ?? {};
    const width = line.width ?? 2;
    const dash = DASHES[line.dash];
    const unit = Math.max(width, 3);
    ctx.setLineDash(dash ? [dash * unit, dash * unit] : []);
    ctx.lineWidth = width;
    ctx.strokeStyle = line.color ?? "#1f77b4";
    ctx.beginPath();
    const tolerance = Math.max(width, 3) / 4;
    const px = new Float64Array(xs.length);
    const py = new Float64Array(xs.length);
    for (let i = 0; i < xs.length; i += 1) {
      px[i] = xs[i] == null ? NaN : xAxis.map(xs[i], true);
      py[i] = ys[i] == null ? NaN : yAxis.map(ys[i], true);
    }
    // each run of drawable points, up to a gap
    for (let start = 0; start < xs.length;) {
      while (start < xs.length && !(Number.isFinite(px[start]) && Number.isFinite(py[start]))) start += 1;
      let end = start;
      while (end < xs.length && Number.isFinite(px[end]) && Number.isFinite(py[end])) end += 1;
      if (end > start) strokeRun(ctx, px, py, start, end, tolerance, size);
      start = end;
    }
    ctx.stroke();
    ctx.setLineDash([]);
  }
  if (mode.includes("markers")) {
    const marker = trace.marker ?? {};
    const r = (marker.size ?? 6) / 2;
    for (let i = 0; i < xs.length; i += 1) {
      if (xs[i] == null || ys[i] == null) continue;
      const px = xAxis.map(xs[i]);
      const py = yAxis.map(ys[i]);
      if (!Number.isFinite(px) || !Number.isFinite(py)) continue;
      const symbol = Array.isArray(marker.symbol) ? marker.symbol[i] : marker.symbol;
      const color = Array.isArray(marker.color) ? marker.color[i] : marker.color ?? "#1f77b4";
      const open = String(symbol ?? "").endsWith("-open") || symbol === "x";
      ctx.beginPath();
      markerPath(ctx, symbol, px, py, r);
      if (!open) {
        ctx.fillStyle = color;
        ctx.fill();
      }
      const lineWidth = marker.line?.width ?? (open ? Math.max(1, symbol === "x" ? r * 0.5 : 1) : 0);
      if (lineWidth > 0) {
        ctx.lineWidth = lineWidth;
        ctx.strokeStyle = open ? color : marker.line?.color ?? color;
        ctx.stroke();
      }
    }
  }
  if (mode.includes("text") && trace.text) {
    ctx.fillStyle = font.color ?? "#444";
    setFont(ctx, font.size ?? 12, font.family);
    ctx.textAlign = "right";
    for (let i = 0; i < xs.length; i += 1) {
      const px = xAxis.map(xs[i]);
      const py = yAxis.map(ys[i]);
      if (Number.isFinite(px) && Number.isFinite(py)) ctx.fillText(trace.text[i] ?? "", px - 4, py - 6);
    }
  }
  ctx.globalAlpha = 1;
}

/** The legend's entries renamed as the figure names its traces. */
function renameLegend(gd, data) {
  const names = data.map((trace) => trace.name);
  const last = legendNames.get(gd);
  if (last && last.length === names.length && last.every((name, i) => name === names[i])) return;
  legendNames.set(gd, names);
  for (const item of gd.querySelectorAll(".legend .traces")) {
    const index = item.__data__?.[0]?.trace?.index;
    const name = data[index]?.name;
    const text = item.querySelector(".legendtext");
    if (text && typeof name === "string" && text.textContent !== name) {
      text.textContent = name;
      text.setAttribute("data-unformatted", name);
    }
  }
}

/**
 * Draw `figure` (styled as the page shows it) over graph `gd`'s plot area; false when
 * Plotly has not laid the graph out yet (its first drawing is Plotly's).
 */
export function drawLive(gd, figure) {
  const full = gd._fullLayout;
  if (!full?._size || !layers(gd).main) return false;
  const shown = gd.data ?? [];
  const traces = figure.data.filter((trace, i) => (shown[i]?.visible ?? true) === true);
  const axes = axesOf(gd, figure, traces);
  if (!axes.x || !axes.y) return false;
  const size = full._size;
  const { canvas, ctx } = canvasOf(gd);
  const ratio = window.devicePixelRatio || 1;
  const width = full.width;
  const height = full.height;
  if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(height * ratio);
    canvas.style.width = `${width}px`;
    canvas.style.height = `${height}px`;
    ctx.lastFont = null; // a resized canvas forgets its font
  }
  const font = { ...full.font, ...(figure.layout.font ?? {}) };
  const background = figure.layout.plot_bgcolor ?? full.plot_bgcolor ?? "#fff";
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  const layout = { axes, size, font, background };
  const layer = staticLayer(gd, layout, canvas);
  if (layer) ctx.drawImage(layer, 0, 0);
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  if (!layer) drawStatic(ctx, layout);
  const fontBefore = ctx.lastFont;
  ctx.save();
  ctx.beginPath();
  ctx.rect(size.l, size.t, size.w, size.h);
  ctx.clip();
  for (const trace of traces) drawTrace(ctx, trace, axes, font, size);
  ctx.restore();
  ctx.lastFont = fontBefore; // restore() brought back the font before the clip
  if (canvas.style.display) canvas.style.display = "";
  // the ranges drawn, for tests: a zoom must hold in the live frames too
  const ranges = JSON.stringify(Object.fromEntries(
    Object.entries(axes).map(([id, axis]) => [id, axis.range])));
  if (canvas.dataset.ranges !== ranges) canvas.dataset.ranges = ranges;
  if (!isLive(gd)) {
    cover(gd, true);
    gd.dataset.live = "true";
  }
  renameLegend(gd, figure.data);
  return true;
}

/** The plot area's background, the grid and zero lines, the tick labels. */
function drawStatic(ctx, { axes, size, font, background }) {
  ctx.fillStyle = background;
  ctx.fillRect(size.l, size.t, size.w, size.h);
  addTicks(axes);
  drawGrid(ctx, axes, size);
  drawLabels(ctx, axes, size, font);
}

/** Graph -> {key, canvas}: what does not move while only the data do (drawStatic),
 *  kept on a canvas of its own once two frames in a row have the same axes. A hand on
 *  a slider often leaves a plot's axes where they were (k, z*, the mass; the plots a
 *  slider does not rescale); each such frame then copies this layer and strokes the
 *  traces, the tick labels neither laid out nor filled again. A frame with new axes
 *  draws them on the live canvas itself (a layer made for one frame costs more). */
const staticLayers = new WeakMap();

function staticLayer(gd, layout, live) {
  const { axes, size, font, background } = layout;
  const key = JSON.stringify([live.width, live.height, size.l, size.t, size.w, size.h, background, font,
    Object.values(axes).map((axis) => [axis.key, axis.range, axis.log, axis.style])]);
  const layer = staticLayers.get(gd) ?? { key: null, canvas: null, drawn: false };
  staticLayers.set(gd, layer);
  if (layer.key !== key) {
    layer.key = key;
    layer.drawn = false;
    return null;
  }
  if (!layer.drawn) {
    layer.canvas ??= document.createElement("canvas");
    const { canvas } = layer;
    const ctx = canvas.getContext("2d");
    if (canvas.width !== live.width || canvas.height !== live.height) {
      canvas.width = live.width;
      canvas.height = live.height;
      ctx.lastFont = null; // a resized canvas forgets its font
    }
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    const ratio = window.devicePixelRatio || 1;
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    drawStatic(ctx, layout);
    layer.drawn = true;
  }
  return layer.canvas;
}

/** The ranges and tick labels a live drawing of `figure` on `gd` uses (for tests). */
export function liveAxes(gd, figure) {
  const shown = gd.data ?? [];
  const traces = figure.data.filter((trace, i) => (shown[i]?.visible ?? true) === true);
  const axes = addTicks(axesOf(gd, figure, traces));
  return Object.fromEntries(Object.entries(axes).map(([id, axis]) => [id, {
    range: axis.range, ticks: axis.ticks.map((tick) => [tick.value, tick.text]),
  }]));
}
