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
/** How the page is shown now, kept here: every live frame asks, and asking the browser
 *  (a media query's `matches`) brings its styles up to date first. */
const shown = { present: false, dark: DARK.matches };
DARK.addEventListener("change", () => { shown.dark = DARK.matches; });

/** Presentation mode on or off: a class on <html> (its root type size) and <body>. A
 *  class, not a :has() rule: :has() made the browser check the root's style again at every
 *  change of the page's text, at every key press. */
export function setPresentation(on) {
  shown.present = on;
  document.documentElement.classList.toggle("present", on);
  document.body.classList.toggle("present", on);
}

/** How the page is shown now: presentation mode and dark mode. */
export function pageStyle() {
  return { ...shown };
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
    .then(() => {
      untab(element);
      if (first) fitToBox(element);
    });
}

/* Plotly sizes a graph to its box once, at its first drawing, and again only when the
   window is resized. The page's layout switches change a box without that: presentation
   mode (larger plots, another grid), a phone's strip, a fit's results shown. Every box
   is watched, and a graph whose box is not the size Plotly laid it out at is laid out
   anew, in the next animation frame (one relayout per graph however many changes came). */
const resized = new Set();
const afterResize = [];
let resizeFrame = null;

/** Whether graph `gd`'s box differs from the size Plotly last laid it out at. */
function outOfSize(gd, width, height) {
  const full = gd._fullLayout;
  // a box with no size is hidden (display: none): laid out once it shows
  return Boolean(full && width && height)
    && (Math.abs(full.width - width) > 1 || Math.abs(full.height - height) > 1);
}

const watcher = typeof ResizeObserver === "undefined" ? null : new ResizeObserver((entries) => {
  for (const { target, contentRect } of entries) {
    if (outOfSize(target, contentRect.width, contentRect.height)) resized.add(target);
  }
  if (resized.size && !resizeFrame) resizeFrame = requestAnimationFrame(relayoutResized);
});

function relayoutResized() {
  resizeFrame = null;
  const graphs = [...resized];
  resized.clear();
  for (const gd of graphs) {
    if (!gd.isConnected || !outOfSize(gd, gd.clientWidth, gd.clientHeight)) continue;
    window.Plotly.relayout(gd, { autosize: true }).then(() => {
      for (const fn of afterResize) fn(gd);
    });
  }
}

function fitToBox(element) {
  watcher?.observe(element);
}

/** Call `fn(graph)` once a graph has been laid out at its box's new size. */
export function onResized(fn) {
  afterResize.push(fn);
}
