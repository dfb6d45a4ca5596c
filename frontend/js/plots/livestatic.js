// What a live drawing (livedraw.js) shows that does not move while only the data do:
// the plot area's background, the grid and zero lines, the tick labels, as Plotly draws
// them; kept on a layer of its own while a plot's axes hold.

import { addTicks } from "./liveaxes.js";

/** The canvas's font, set only when it changes: each assignment parses the font anew
 *  and brings the page's styles up to date. */
export function setFont(ctx, size, family) {
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

/** The plot area's background, the grid and zero lines, the tick labels. */
export function drawStatic(ctx, { axes, size, font, background }) {
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

/** What the static layer of `layout` on a canvas of `width` × `height` pixels shows,
 *  as a string: two layouts with the same key draw the same pixels. */
export function staticKey({ axes, size, font, background }, width, height) {
  return JSON.stringify([width, height, size.l, size.t, size.w, size.h, background, font,
    Object.values(axes).map((axis) => [axis.key, axis.range, axis.log, axis.style])]);
}

/** The static layer of graph `gd` for `layout` (its staticKey `key`) on canvas `live`,
 *  or null while it is not kept (its axes are new). */
export function staticLayer(gd, layout, live, key) {
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
