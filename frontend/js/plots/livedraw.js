// A figure drawn on a canvas inside a Plotly graph, for the frames of a moving hand:
// Plotly needs 13–24 ms to redraw one of these plots (benchmarks/ui_latency.py), this
// 0.2–2 ms. The canvas lies between Plotly's two SVG layers, in the graph's own plot area
// (Plotly's last layout: size and margins, which a legend may have widened): under it
// the paper, over it the legend and the axis titles, whose names are brought up to date.
// Backgrounds, grid, zero lines, traces and tick labels are drawn as Plotly draws them,
// with Plotly's own ranges and ticks (axes.js), while Plotly's layers for them are hidden.
// A person's zoom is kept, and traces hidden from the legend stay hidden.

import { axesOf, shownTraces } from "./liveaxes.js";
import { canvasOf, layers, renameLegend, showLive } from "./livelayers.js";
import { drawStatic, staticLayer } from "./livestatic.js";
import { drawTrace } from "./livetraces.js";

/**
 * Draw `figure` (styled as the page shows it) over graph `gd`'s plot area; false when
 * Plotly has not laid the graph out yet (its first drawing is Plotly's).
 */
export function drawLive(gd, figure) {
  const full = gd._fullLayout;
  if (!full?._size || !layers(gd).main) return false;
  const traces = shownTraces(gd, figure);
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
  showLive(gd);
  renameLegend(gd, figure.data);
  return true;
}
