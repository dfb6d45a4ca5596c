// The live canvas's place in a Plotly graph (livedraw.js draws on it): found in the
// graph's container between Plotly's two SVG layers, Plotly's layers it stands in for
// hidden while it shows, and the legend's names kept as the live figure names its traces.

const legendNames = new WeakMap(); // graph -> the names a live frame last gave its legend
/** Graph -> its legend's entries [{index: the trace's, text: its name's element}], found
 *  once while a hand moves (a drag of k renames two legends every frame), found again
 *  once Plotly has drawn the graph. */
const legendItems = new WeakMap();

/** Plotly's layers that the canvas stands in for, in the graph's first SVG. */
const COVERED = [".bglayer", ".layer-below", ".cartesianlayer"];

/** Graph -> its Plotly container, first SVG, live canvas and that canvas's context,
 *  found once (each frame asked the DOM five times a plot), found again when Plotly has
 *  replaced them. */
const found = new WeakMap();

export function layers(gd) {
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

export function canvasOf(gd) {
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

/** The canvas shown instead of Plotly's drawing (once a live frame is on it). */
export function showLive(gd) {
  if (isLive(gd)) return;
  cover(gd, true);
  gd.dataset.live = "true";
}

/** Plotly's drawing shown again (once Plotly has drawn the figure the canvas showed). */
export function clearLive(gd) {
  if (!isLive(gd)) return;
  gd.dataset.live = "false";
  legendNames.delete(gd); // Plotly's legend holds its own names again
  legendItems.delete(gd);
  const { canvas } = layers(gd);
  if (canvas) canvas.style.display = "none";
  cover(gd, false);
}

/** The legend's entries renamed as the figure names its traces. */
export function renameLegend(gd, data) {
  const names = data.map((trace) => trace.name);
  const last = legendNames.get(gd);
  if (last && last.length === names.length && last.every((name, i) => name === names[i])) return;
  legendNames.set(gd, names);
  let items = legendItems.get(gd);
  if (!items || !items.every(({ text }) => text.isConnected)) {
    items = [...gd.querySelectorAll(".legend .traces")].map((item) => ({
      index: item.__data__?.[0]?.trace?.index, text: item.querySelector(".legendtext"),
    })).filter(({ text }) => text);
    legendItems.set(gd, items);
  }
  for (const { index, text } of items) {
    const name = data[index]?.name;
    if (typeof name === "string" && text.textContent !== name) {
      text.textContent = name;
      text.setAttribute("data-unformatted", name);
    }
  }
}
