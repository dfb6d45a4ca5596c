// A figure's traces drawn on a live canvas (livedraw.js) as Plotly draws them: lines
// (dashed, simplified as Plotly simplifies them), filled regions, markers of Plotly's
// shapes, text.

import { setFont } from "./livestatic.js";

const DASHES = { dash: 3, dot: 1, longdash: 5 };

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

/** The pixel coordinates of a line, in buffers kept between traces and frames: a new
 *  pair a trace a frame was most of what drawing gave the garbage collector. */
let pixels = [new Float64Array(0), new Float64Array(0)];

function pixelBuffers(length) {
  if (pixels[0].length < length) {
    const size = 2 ** Math.ceil(Math.log2(length));
    pixels = [new Float64Array(size), new Float64Array(size)];
  }
  return pixels;
}

/** The pixels of `values` on `axis` into `out` (NaN for a gap): a linear axis by its
 *  scale and offset, a log axis through its map. */
function fillPixels(out, values, axis) {
  if (axis.log) {
    for (let i = 0; i < values.length; i += 1) {
      out[i] = values[i] == null ? NaN : axis.map(values[i], true);
    }
    return;
  }
  const { scale, offset } = axis;
  for (let i = 0; i < values.length; i += 1) {
    const value = values[i];
    out[i] = value == null ? NaN : offset + scale * value;
  }
}

export function drawTrace(ctx, trace, axes, font, size) {
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
    const [px, py] = pixelBuffers(xs.length);
    fillPixels(px, xs, xAxis);
    fillPixels(py, ys, yAxis);
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
