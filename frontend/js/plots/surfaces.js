// Where the explorer's figures become pixels, two ways:
//   live    while a hand moves a slider: the figure drawn on a canvas in the graph's own
//           axes (livedraw.js), 0.2–2 ms a plot;
//           A frame one key press away may be painted ahead (prepare), while the page
//           is idle; the press then copies it.
//   settled once it stops: Plotly.react, 13–24 ms a plot, skipped when the graph holds
//           the figure already; the canvas is then put away.
// A graph shows the settled drawing except between a live frame and the next settle.

import { drawFigure, onResized } from "./draw.js";
import { drawLive, paintAhead } from "./livedraw.js";
import { clearLive, isLive } from "./livelayers.js";

const drawn = {}; // plot id -> {data, layoutKey} the graph was last drawn with by Plotly
const drawnLive = {}; // plot id -> the figure its live canvas shows

/** Plotly.react calls, live drawings, live frames copied from a frame painted ahead,
 *  frames painted ahead. */
export const surfaceStats = { reacts: 0, live: 0, ahead: 0, painted: 0 };

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

const graphs = new Map(); // plot id -> its graph element, looked up once
function graph(id) {
  let gd = graphs.get(id);
  if (!gd?.isConnected) {
    gd = document.getElementById(`plot-${id}`);
    graphs.set(id, gd);
  }
  return gd;
}

/**
 * Show `figure` (styled as the page shows it) on plot `id` with Plotly: nothing when the
 * graph holds it already, else `Plotly.react`; then the live canvas is put away.
 * `config`: Plotly's config, given with a graph's first drawing; `current()` false when
 * a live frame of a newer state came meanwhile (its canvas then stays).
 */
export function settle(id, figure, config, current = () => true) {
  const gd = graph(id);
  deferred.delete(gd);
  visible(gd); // watched from its first drawing on
  // the layout as JSON, taken before Plotly writes its computed ranges into it
  const wanted = { data: figure.data, layoutKey: JSON.stringify(figure.layout) };
  const last = drawn[id];
  if (last && last.gd === gd && last.layoutKey === wanted.layoutKey && sameFigure(last.data, wanted.data)) {
    if (current()) clearLive(gd);
    return Promise.resolve();
  }
  drawn[id] = { ...wanted, gd };
  surfaceStats.reacts += 1;
  return drawFigure(gd, figure, { config, shown: true }).then(() => {
    if (current()) clearLive(gd);
  });
}

const inView = new Map(); // graph -> whether it is in the viewport (IntersectionObserver)
const deferred = new Map(); // graph -> [plot id, the figure] to draw live once it is in view
let viewport = null;

/** Whether graph `gd` is in the viewport (true until the observer first says, which it
 *  does soon after a graph's first drawing). A live frame of a graph out of view is
 *  drawn once it comes into view: while a hand moves the loop's friction, the model's
 *  four plots above it cost each frame their drawing. */
function visible(gd) {
  viewport ??= new IntersectionObserver((entries) => {
    for (const entry of entries) {
      inView.set(entry.target, entry.isIntersecting);
      const waiting = entry.isIntersecting && deferred.get(entry.target);
      if (waiting) live(...waiting);
    }
  });
  if (!inView.has(gd)) {
    inView.set(gd, true);
    viewport.observe(gd);
  }
  return inView.get(gd);
}

/** Frames painted ahead, by graph: [{figure, frame}], the last used last. The states
 *  one key press away either way, the one shown and the one left: with three, the
 *  state a press leaves was dropped for the one ahead, and painted again behind it. */
const ahead = new WeakMap();
const AHEAD_KEPT = 4;

/** Draw `figure` on plot `id`'s live canvas (nothing when it shows it already: while
 *  the mass moves, only the ramp changes; later when the graph is out of view); false
 *  when the graph has no Plotly layout yet (its first drawing is Plotly's). */
export function live(id, figure) {
  const gd = graph(id);
  deferred.delete(gd);
  if (isLive(gd) && drawnLive[id]?.gd === gd && sameFigure(drawnLive[id].figure, figure)) return true;
  if (gd._fullLayout?._size && !visible(gd)) {
    deferred.set(gd, [id, figure]);
    return true;
  }
  const frames = ahead.get(gd) ?? [];
  const index = frames.findIndex((entry) => sameFigure(entry.figure, figure));
  const done = drawLive(gd, figure, frames[index]?.frame);
  if (done) {
    drawnLive[id] = { gd, figure };
    surfaceStats.live += 1;
  }
  if (done === "ahead") {
    surfaceStats.ahead += 1;
    frames.push(...frames.splice(index, 1));
  }
  return Boolean(done);
}

/** Paint `figure` ahead for plot `id` (nothing when it is painted already for the graph
 *  as it is, or the graph is out of view or not laid out): a live frame of an equal
 *  figure then copies it rather than drawing. */
export function prepare(id, figure) {
  const gd = graph(id);
  if (!gd?._fullLayout?._size || !visible(gd)) return;
  const frames = ahead.get(gd) ?? [];
  ahead.set(gd, frames);
  const index = frames.findIndex((entry) => sameFigure(entry.figure, figure));
  const old = index >= 0 ? frames.splice(index, 1)[0]
    : frames.length >= AHEAD_KEPT ? frames.shift() : null;
  const reuse = index >= 0 ? old.frame : old && { key: null, canvas: old.frame.canvas };
  const frame = paintAhead(gd, figure, reuse);
  if (!frame) return;
  frames.push({ figure, frame });
  if (frame !== reuse) surfaceStats.painted += 1;
}

// a graph laid out at a new size while it shows a live frame: the frame drawn again at it
onResized((gd) => {
  const id = gd.id.replace(/^plot-/, "");
  if (!isLive(gd) || drawnLive[id]?.gd !== gd) return;
  clearLive(gd);
  drawLive(gd, drawnLive[id].figure);
});
