// The registry of the explorer's views: every plot the render path draws is one entry.
//
// A view is {id, figure(ctx), caption, source, request?, redraws?, plots?}:
//   id       its plot is the element #plot-<id>;
//   figure   a pure function of ctx = {frame, state} (and the page's app data) to a fresh
//            Plotly figure {data, layout}, titled in the state's units;
//   caption  (state, plot) → the parameters the plot is drawn with, units included
//            ("Fc = 1 N, V = 100 m/s, …"): the caption of its exported images;
//   source   "frame": drawn from each /api/explore frame (the four model plots);
//            "request": drawn from the answer of its own request, `request` =
//            {url, body(state) → JSON body, debounceMs}, asked for once the frame of a
//            state is drawn, the previous one aborted (viewrequests.js);
//            `request.live(state)` true: asked for live at every change of a valid
//            state, not only when the model's curves stay (a quick answer: the loop);
//   figures  instead of figure, for a view that draws several plots from one answer:
//            ctx → {plot id: figure} (the control loop's three plots), `plots` their ids;
//   redraws  frame views whose figure shows this view's answer too (e.g. the ramp's
//            simulated path over the phase family), redrawn when it arrives.
// Overlays add traces to the figures of other views (pinned curves, a sweep, measured
// points): registerOverlay(fn), fn(figures, ctx) returning nothing, replacing figures in
// place. A new view (a control loop, say) registers itself in its own module; the render
// path walks the registry and needs no change.

const registry = new Map();
const overlays = [];

export function registerView(view) {
  registry.set(view.id, view);
}

export function viewOf(id) {
  return registry.get(id);
}

/** The view that draws plot `plot` (its own, or one of its `plots`). */
export function viewOfPlot(plot) {
  return registry.get(plot) ?? [...registry.values()].find((view) => view.plots?.includes(plot));
}

/** Ids of the views drawn from the explore frame, in registration order. */
export function frameViewIds() {
  return [...registry.values()].filter((view) => view.source === "frame").map((view) => view.id);
}

/** The views with a request of their own. */
export function requestViews() {
  return [...registry.values()].filter((view) => view.request);
}

export function registerOverlay(overlay) {
  overlays.push(overlay);
}

/**
 * The figures the page shows for `state`, whose curves `frame` holds (every frame view,
 * or those in `ids`): each view's figure, then every overlay applied.
 */
export function pageFigures(frame, state, ids = frameViewIds()) {
  const ctx = { frame, state };
  const out = {};
  for (const id of ids) out[id] = registry.get(id).figure(ctx);
  for (const overlay of overlays) overlay(out, ctx);
  return out;
}
