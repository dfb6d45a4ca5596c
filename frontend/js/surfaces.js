// Where the explorer's figures become pixels. Every plot is a Plotly graph, `#plot-<id>`,
// that is redrawn only when its figure changed. A plot may also have a second graph in
// the same place, hidden (`#plot-<id>-ahead`): drawn ahead, while the page is idle, with
// the figure the next arrow step will show. When that step comes, the two trade places:
// a key press that would wait for Plotly (6–13 ms a plot here) waits for none.
//
// Drawn ahead is exact by construction: the hidden graph is shown only when the figure
// asked for is equal to the one it was drawn with, and only while the person has not
// zoomed or hidden traces in the shown graph (which the hidden one would not know of).

import { AXIS_KEY, drawFigure } from "./draw.js";

/** Attributes that belong to the graph on screen, not to either element. */
const SHOWN = ["role", "aria-label"];

const surfaces = {}; // plot id -> {front, back, frontDrawn, backDrawn, backReady}

export const surfaceStats = { reacts: 0, swaps: 0, drawnAhead: 0 };

/** Deep equality of figures; arrays element by element (they come fresh each frame). */
function sameFigure(a, b) {
  if (a === b) return true;
  if (typeof a !== "object" || typeof b !== "object" || a === null || b === null) {
    return Number.isNaN(a) && Number.isNaN(b);
  }
  if (Array.isArray(a) !== Array.isArray(b)) return false;
  if (Array.isArray(a)) {
    if (a.length !== b.length) return false;
    for (let i = 0; i < a.length; i += 1) {
      const x = a[i];
      const y = b[i];
      if (x !== y && !(typeof x === "object" && sameFigure(x, y))) return false;
    }
    return true;
  }
  const keys = Object.keys(a);
  if (keys.length !== Object.keys(b).length) return false;
  return keys.every((key) => key in b && sameFigure(a[key], b[key]));
}

/** What a graph was last drawn with: the traces, and the layout as JSON taken before
 *  Plotly writes its computed ranges into the layout object. */
function drawing(figure) {
  return { data: figure.data, layoutKey: JSON.stringify(figure.layout) };
}

function shows(drawn, wanted) {
  return Boolean(drawn) && drawn.layoutKey === wanted.layoutKey
    && sameFigure(drawn.data, wanted.data);
}

function surface(id) {
  const front = document.getElementById(`plot-${id}`);
  if (!surfaces[id] || surfaces[id].front !== front) {
    surfaces[id] = { front, back: null, frontDrawn: null, backDrawn: null, backReady: false };
  }
  return surfaces[id];
}

/** Give each plot in `ids` a hidden graph in the same place, to draw ahead into. */
export function addAheadGraphs(ids) {
  for (const id of ids) {
    const entry = surface(id);
    if (entry.back) continue;
    const stack = document.createElement("div");
    stack.className = "plot-stack";
    entry.front.replaceWith(stack);
    const back = document.createElement("div");
    back.className = "plot-ahead";
    back.id = `plot-${id}-ahead`;
    back.setAttribute("aria-hidden", "true");
    back.inert = true;
    stack.append(entry.front, back);
    entry.back = back;
  }
}

/**
 * True when the person has left the graph as drawn: no axis zoomed or panned, no trace
 * hidden from its legend. Plotly writes both into the graph's own `layout` and `data`
 * (and keeps them across redraws through `uirevision`).
 */
function asDrawn(graph) {
  const layout = graph.layout ?? {};
  const zoomed = Object.keys(layout).some(
    (key) => AXIS_KEY.test(key) && layout[key]?.autorange === false);
  const hidden = (graph.data ?? []).some(
    (trace) => trace.visible !== undefined && trace.visible !== true);
  return !zoomed && !hidden;
}

/** The hidden graph takes the shown one's place (and its id and name), and back. */
function swap(entry) {
  const { front, back } = entry;
  const shownId = front.id;
  front.id = back.id;
  back.id = shownId;
  for (const name of SHOWN) {
    const value = front.getAttribute(name);
    if (value !== null) back.setAttribute(name, value);
    front.removeAttribute(name);
  }
  front.classList.replace("plot", "plot-ahead");
  front.setAttribute("aria-hidden", "true");
  front.inert = true;
  back.classList.replace("plot-ahead", "plot");
  back.removeAttribute("aria-hidden");
  back.inert = false;
  Object.assign(entry, {
    front: back, back: front, frontDrawn: entry.backDrawn, backDrawn: entry.frontDrawn,
    backReady: true,
  });
}

/**
 * Show `figure` (styled as the page shows it) on plot `id`: nothing when it is shown
 * already, the graph drawn ahead when that one holds it, else `Plotly.react`.
 * `config`: Plotly's config, given with a graph's first drawing.
 */
export function show(id, figure, config) {
  const entry = surface(id);
  const wanted = drawing(figure);
  if (shows(entry.frontDrawn, wanted)) return Promise.resolve();
  if (entry.back && entry.backReady && shows(entry.backDrawn, wanted) && asDrawn(entry.front)) {
    swap(entry);
    surfaceStats.swaps += 1;
    return Promise.resolve();
  }
  entry.frontDrawn = wanted;
  surfaceStats.reacts += 1;
  return drawFigure(entry.front, figure, { config, shown: true });
}

/**
 * Draw `figure` into plot `id`'s hidden graph, unless one of its graphs holds it
 * already or the shown graph has been zoomed (the hidden one could not be shown).
 * The drawing's promise, or null when there was nothing to draw.
 */
export function drawAhead(id, figure, config) {
  const entry = surface(id);
  if (!entry.back || !asDrawn(entry.front)) return null;
  const wanted = drawing(figure);
  if (shows(entry.frontDrawn, wanted) || shows(entry.backDrawn, wanted)) return null;
  entry.backDrawn = wanted;
  entry.backReady = false;
  surfaceStats.drawnAhead += 1;
  return drawFigure(entry.back, figure, { config, shown: true }).then(() => {
    if (entry.backDrawn === wanted) entry.backReady = true;
  });
}

/** True when one of plot `id`'s graphs shows `figure` or is ready to. */
export function holds(id, figure) {
  const entry = surface(id);
  const wanted = drawing(figure);
  return shows(entry.frontDrawn, wanted) || (entry.backReady && shows(entry.backDrawn, wanted));
}
