// Export what a plot shows so that it explains itself away from the page: its traces as
// CSV (one row per plotted point, under '# ' lines with the title and the parameters),
// and the figure as PNG or SVG with its title and a caption line of the parameters it
// was drawn with, units included. A plot is described by {name (the file's), title,
// caption, figure (plain: not styled for the page)}; the explorer's views and the data
// panel describe theirs.

import { forPlotly, pageStyle } from "./draw.js";
import { styled } from "./plots.js";

/** Image sizes [px]: a slide's width, the plot's proportions. */
const IMAGE = { width: 1200, height: 720 };
/** Characters in a caption line before it wraps at a comma. */
const CAPTION_LINE = 120;

function csvField(text) {
  const s = String(text);
  return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

/** The axis titles of a figure: {x, y, y2?}. */
export function figureAxes(figure) {
  const title = (axis) => figure.layout[axis]?.title?.text ?? figure.layout[axis]?.title;
  const axes = { x: title("xaxis") ?? "x", y: title("yaxis") ?? "y" };
  if (figure.layout.yaxis2) axes.y2 = title("yaxis2") ?? "y2";
  // a log axis says so in its title; the values are plain
  return Object.fromEntries(Object.entries(axes).map(([key, text]) => [key, String(text).replace(/ \(log\)$/, "")]));
}

/**
 * CSV text of plotted traces: columns series, <x axis>, <y axis> (and <right y axis>:
 * a trace drawn on it writes its values there); gaps are skipped. `meta`: lines above
 * the header, "# key: value".
 */
export function tracesToCsv(traces, axes, meta = {}) {
  const right = Boolean(axes.y2);
  const lines = Object.entries(meta).map(([key, value]) => `# ${key}: ${String(value).replace(/\s*\n\s*/g, " ")}`);
  lines.push(["series", axes.x, axes.y, ...(right ? [axes.y2] : [])].map(csvField).join(","));
  for (const trace of traces) {
    const xs = trace.x ?? [];
    const ys = trace.y ?? [];
    const onRight = right && trace.yaxis === "y2";
    for (let i = 0; i < xs.length; i += 1) {
      if (xs[i] == null || ys[i] == null) continue;
      const values = onRight ? [xs[i], "", ys[i]] : [xs[i], ys[i], ...(right ? [""] : [])];
      lines.push([csvField(trace.name ?? ""), ...values].join(","));
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

/** A caption broken into lines at commas, none much over CAPTION_LINE characters. */
function wrap(caption) {
  const lines = [];
  for (const part of caption.split(", ")) {
    const last = lines.length - 1;
    if (last >= 0 && lines[last].length + part.length + 2 <= CAPTION_LINE) lines[last] += `, ${part}`;
    else lines.push(part);
  }
  return lines;
}

/** The figure of an exported image: the plain figure styled as the page is (large type in
 *  presentation mode; always on white: a slide has its own background), its title and
 *  the caption lines above the plot. */
export function imageFigure({ title, caption, figure }, style = pageStyle()) {
  const { data, layout } = styled(figure, { present: style.present, dark: false });
  const lines = wrap(caption);
  const size = style.present ? 18 : 13;
  const top = Math.round(2.2 * size + 1.45 * size * lines.length + 14);
  return {
    data,
    layout: {
      ...layout,
      title: {
        text: title, x: 0, xref: "paper", xanchor: "left", y: 1, yref: "container", yanchor: "top",
        pad: { t: 10, l: 4 }, font: { size: Math.round(1.4 * size) },
        subtitle: { text: lines.join("<br>"), font: { size, color: "#444" } },
      },
      margin: { ...(layout.margin ?? {}), t: top + (layout.margin?.t ?? 8) },
      paper_bgcolor: "#ffffff",
      plot_bgcolor: "#ffffff",
      uirevision: undefined,
    },
  };
}

/** A plot's traces as CSV, titled and captioned. */
export function exportCsv(described) {
  const { name, title, caption, figure } = described;
  const csv = tracesToCsv(figure.data, figureAxes(figure), { title, parameters: caption });
  download(`breakaway-${name}.csv`, new Blob([csv], { type: "text/csv" }));
}

/** The image of a plot (format "png" or "svg") as a Blob. */
export async function imageBlob(described, format) {
  const { data, layout } = imageFigure(described);
  const { width, height } = IMAGE;
  const url = await window.Plotly.toImage(
    { data, layout: forPlotly({ ...layout, width, height }), config: { staticPlot: true } },
    { format, width, height, scale: format === "png" ? 2 : 1 },
  );
  const [head, body] = url.split(",", 2);
  if (head.endsWith(";base64")) {
    const bytes = Uint8Array.from(atob(body), (c) => c.charCodeAt(0));
    return new Blob([bytes], { type: `image/${format}` });
  }
  return new Blob([decodeURIComponent(body)], { type: "image/svg+xml" });
}

/** A plot's image, titled and captioned, saved as PNG or SVG. */
export async function exportImage(described, format) {
  download(`breakaway-${described.name}.${format}`, await imageBlob(described, format));
}

const FORMATS = ["csv", "png", "svg"];

/** The CSV, PNG and SVG buttons of plot `plot`, named "Export <name> as PNG". */
export function exportButtons(plot, name) {
  return FORMATS.map((format) => {
    const button = document.createElement("button");
    button.type = "button";
    button.dataset.export = format;
    button.dataset.plot = plot;
    button.setAttribute("aria-label", `Export ${name} as ${format.toUpperCase()}`);
    button.textContent = format.toUpperCase();
    return button;
  });
}

/** Give every [data-exports="<plot>"][data-name] under `root` its plot's buttons. */
export function addExportButtons(root) {
  for (const host of root.querySelectorAll("[data-exports]")) {
    host.append(...exportButtons(host.dataset.exports, host.dataset.name));
  }
}

/** Wire the export buttons under `root` ([data-export="csv|png|svg"][data-plot]):
 *  `describe(plot)` gives the plot's description, or null when it shows nothing yet. */
export function wireExports(root, describe) {
  root.addEventListener("click", (event) => {
    const button = event.target.closest?.("[data-export][data-plot]");
    if (!button || !root.contains(button)) return;
    const described = describe(button.dataset.plot);
    if (!described) return;
    if (button.dataset.export === "csv") exportCsv(described);
    else exportImage(described, button.dataset.export);
  });
}
