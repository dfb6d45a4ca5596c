// A figure drawn on a canvas inside a Plotly graph, for the frames of a moving hand:
// Plotly needs 13–24 ms to redraw one of these plots (benchmarks/ui_latency.py), this
// 0.2–2 ms. The canvas lies between Plotly's two SVG layers, in the graph's own plot area
// (Plotly's last layout: size and margins, which a legend may have widened): under it
// the paper, over it the legend and the axis titles, whose names are brought up to date.
// Backgrounds, grid, zero lines, traces and tick labels are drawn as Plotly draws them,
// with Plotly's own ranges and ticks (axes.js), while Plotly's layers for them are hidden.
// A person's zoom is kept, and traces hidden from the legend stay hidden.
// A frame may also be painted ahead, while the page is idle, on a canvas of its own
// (paintAhead): the frame of a state one key press away, which the press then copies.

import { axesOf, shownTraces } from "./liveaxes.js";
import { canvasOf, layers, renameLegend, showLive } from "./livelayers.js";
import { drawStatic, staticKey, staticLayer } from "./livestatic.js";
import { drawTrace } from "./livetraces.js";

/** What a frame of `figure` on graph `gd` paints but its traces: the graph's plot
 *  area, axes, font and background, the canvas's size in pixels; null while Plotly has
 *  not laid the graph out (its first drawing is Plotly's). */
function frameOf(gd, figure) {
  const full = gd._fullLayout;
  if (!full?._size || !layers(gd).main) return null;
  const traces = shownTraces(gd, figure);
  const axes = axesOf(gd, figure, traces);
  if (!axes.x || !axes.y) return null;
  const ratio = window.devicePixelRatio || 1;
  return {
    traces, axes, ratio,
    size: full._size,
    font: { ...full.font, ...(figure.layout.font ?? {}) },
    background: figure.layout.plot_bgcolor ?? full.plot_bgcolor ?? "#fff",
    width: full.width,
    height: full.height,
    pixels: [Math.round(full.width * ratio), Math.round(full.height * ratio)],
  };
}

/** The canvas sized for `frame` (a resized canvas is cleared, and forgets its font). */
function fit(canvas, ctx, frame) {
  const [width, height] = frame.pixels;
  if (canvas.width === width && canvas.height === height) return;
  canvas.width = width;
  canvas.height = height;
  ctx.lastFont = null;
}

/** The frame painted on `ctx`: the static `layer` copied (else the static parts drawn),
 *  then the traces, clipped to the plot area. */
function paint(ctx, frame, layer) {
  const { size, ratio } = frame;
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.clearRect(0, 0, ctx.canvas.width, ctx.canvas.height);
  if (layer) ctx.drawImage(layer, 0, 0);
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  if (!layer) drawStatic(ctx, frame);
  const fontBefore = ctx.lastFont;
  ctx.save();
  ctx.beginPath();
  ctx.rect(size.l, size.t, size.w, size.h);
  ctx.clip();
  for (const trace of frame.traces) drawTrace(ctx, trace, frame.axes, frame.font, size);
  ctx.restore();
  ctx.lastFont = fontBefore; // restore() brought back the font before the clip
}

/** Everything a frame's pixels depend on but its figure's traces, as a string: the
 *  static layer's key and which traces the legend shows. */
function frameKey(gd, frame, layerKey = staticKey(frame, ...frame.pixels)) {
  const visible = (gd.data ?? []).map((trace) => trace.visible ?? true);
  return `${layerKey}${JSON.stringify(visible)}`;
}

/**
 * Draw `figure` (styled as the page shows it) over graph `gd`'s plot area; false when
 * Plotly has not laid the graph out yet (its first drawing is Plotly's). `ahead`: a
 * frame painted ahead (paintAhead) for a figure equal to `figure`, copied when the
 * graph is still as it was painted for ("ahead" returned), else the figure is drawn
 * (true returned).
 */
export function drawLive(gd, figure, ahead = null) {
  const frame = frameOf(gd, figure);
  if (!frame) return false;
  const { canvas, ctx } = canvasOf(gd);
  fit(canvas, ctx, frame);
  if (canvas.style.width !== `${frame.width}px` || canvas.style.height !== `${frame.height}px`) {
    canvas.style.width = `${frame.width}px`;
    canvas.style.height = `${frame.height}px`;
  }
  const key = staticKey(frame, canvas.width, canvas.height);
  const copied = Boolean(ahead) && ahead.key === frameKey(gd, frame, key);
  if (copied) {
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    ctx.drawImage(ahead.canvas, 0, 0);
  } else {
    paint(ctx, frame, staticLayer(gd, frame, canvas, key));
  }
  if (canvas.style.display) canvas.style.display = "";
  // the ranges drawn, for tests: a zoom must hold in the live frames too
  const ranges = JSON.stringify(Object.fromEntries(
    Object.entries(frame.axes).map(([id, axis]) => [id, axis.range])));
  if (canvas.dataset.ranges !== ranges) canvas.dataset.ranges = ranges;
  showLive(gd);
  renameLegend(gd, figure.data);
  return copied ? "ahead" : true;
}

/**
 * A frame of `figure` painted ahead for graph `gd`, on a canvas of its own, to be
 * copied by drawLive: {key, canvas}; `reuse` a frame painted ahead before whose canvas
 * may be painted again (returned as it is when it holds this frame already); null
 * while Plotly has not laid the graph out. The static layer is drawn, not kept: the
 * frames painted ahead are those of other axes than the shown one's, often.
 */
export function paintAhead(gd, figure, reuse = null) {
  const frame = frameOf(gd, figure);
  if (!frame) return null;
  const key = frameKey(gd, frame);
  if (reuse?.key === key) return reuse;
  const canvas = reuse?.canvas ?? document.createElement("canvas");
  const ctx = canvas.getContext("2d");
  fit(canvas, ctx, frame);
  paint(ctx, frame, null);
  return { key, canvas };
}
