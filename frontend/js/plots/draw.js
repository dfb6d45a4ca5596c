// Where figures meet Plotly, for the explorer and the data panel alike: the toolbar this
// app wants (no cloud or Chart Studio buttons, no logo), the page's presentation mode and
// colour scheme applied to the figure, and the modebar kept out of the keyboard path.

import { styled } from "./plots.js";

export const PLOT_CONFIG = {
  responsive: true,
  displaylogo: false,
  showSendToCloud: false,
  showEditInChartStudio: false,
  showLink: false,
  modeBarButtonsToRemove: ["select2d", "lasso2d", "sendDataToCloud"],
};

const DARK = window.matchMedia("(prefers-color-scheme: dark)");

/** How the page is shown now: presentation mode (a class on <body>) and dark mode. */
export function pageStyle() {
  return { present: document.body.classList.contains("present"), dark: DARK.matches };
}

/** Call `redraw` when the system switches between light and dark. */
export function onSchemeChange(redraw) {
  DARK.addEventListener("change", redraw);
}

/** A layout key that holds an axis (xaxis, yaxis2, …). */
export const AXIS_KEY = /^[xy]axis\d*$/;

/** Plotly's modebar buttons are links in the tab order; the page's own buttons (export,
 *  play, downloads) do what they do, so the modebar leaves the keyboard path. */
function untab(element) {
  for (const button of element.querySelectorAll(".modebar-btn")) button.tabIndex = -1;
}

/**
 * What Plotly would otherwise find out on every redraw, stated once: every axis is
 * numeric (unless the figure says log), so Plotly does not scan each data array for
 * dates and categories; tick labels may overflow the axis ends (the margins leave room),
 * so it does not measure every label to hide the ones that would. With the config given
 * once (below), 3–5 ms of a key press (benchmarks/bench_page.py).
 */
export function forPlotly(layout) {
  const out = { ...layout };
  for (const key of Object.keys(layout)) {
    if (AXIS_KEY.test(key)) {
      out[key] = { type: "linear", ticklabeloverflow: "allow", ...layout[key] };
    }
  }
  return out;
}

/** Draw a figure as the page is shown (`styled` already applied when `shown`). The
 *  config goes with the first drawing only: given to every `Plotly.react`, Plotly
 *  compares it with the old one and reads the plot's size, a forced layout per plot. */
export function drawFigure(element, figure, { config = {}, shown = false } = {}) {
  const { data, layout } = shown ? figure : styled(figure, pageStyle());
  const first = !element._context;
  return window.Plotly.react(element, data, forPlotly(layout),
    first ? { ...PLOT_CONFIG, ...config } : undefined)
    .then(() => untab(element));
}
