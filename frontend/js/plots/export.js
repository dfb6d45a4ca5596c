// Export what a plot shows: its traces as CSV (one row per plotted point), or a PNG.

import { viewOf } from "../page/views.js";

function csvField(text) {
  const s = String(text);
  return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

/** CSV text of plotted traces: columns series, <x axis>, <y axis>; gaps are skipped. */
export function tracesToCsv(traces, axes) {
  const lines = [["series", axes.x, axes.y].map(csvField).join(",")];
  for (const trace of traces) {
    const xs = trace.x ?? [];
    const ys = trace.y ?? [];
    for (let i = 0; i < xs.length; i += 1) {
      if (xs[i] == null || ys[i] == null) continue;
      lines.push(`${csvField(trace.name ?? "")},${xs[i]},${ys[i]}`);
    }
  }
  return `${lines.join("\n")}\n`;
}

/** Save `blob` as `filename` through a temporary link. */
export function download(filename, blob) {
  const url = URL.createObjectURL(blob);
  const link = document.createElement("a");
  link.href = url;
  link.download = filename;
  document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

export function exportCsv(plot) {
  const graph = document.getElementById(`plot-${plot}`);
  const csv = tracesToCsv(graph.data ?? [], viewOf(plot).axes);
  download(`breakaway-${plot}.csv`, new Blob([csv], { type: "text/csv" }));
}

export function exportPng(plot) {
  const graph = document.getElementById(`plot-${plot}`);
  return window.Plotly.downloadImage(graph, {
    format: "png", filename: `breakaway-${plot}`, width: 900, height: 600, scale: 1,
  });
}
