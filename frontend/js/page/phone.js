// On a phone the plots stay at the top of the screen while the controls scroll under
// them (explorer.css), one plot in view at a time: swiped, or picked with the buttons
// above it. A slider that does not move the plot in view brings one it moves, as soon
// as it is touched or focused, so the plot being explored is the one in view.
// #plots data-in-view names it.

import { $ } from "./store.js";

const PHONE = window.matchMedia("(max-width: 720px)");
const MODEL = ["stribeck", "hysteresis", "phase", "breakaway"];
/** The plots each control moves, the first the one to bring into view; the ramp
 *  experiment follows every parameter. Views add theirs (plotMovedBy). */
const PLOTS_OF = {
  Fc: [...MODEL, "ramp"], Fs: [...MODEL, "ramp"],
  V: ["stribeck", "breakaway", "ramp"],
  delta: ["stribeck", "hysteresis", "breakaway", "ramp"],
  sigma: ["stribeck", "hysteresis", "breakaway", "ramp"],
  k: ["breakaway", "phase", "ramp"],
  s: ["hysteresis", "phase", "breakaway", "ramp"],
  z_ba: ["breakaway", "phase", "ramp"],
  F_hat: ["breakaway", "phase", "ramp"],
  m: ["ramp"],
};

/** Plot `id` moves with the controls `names` (a data-param, or an element's id). */
export function plotMovedBy(id, names) {
  for (const name of names) PLOTS_OF[name] = [...(PLOTS_OF[name] ?? []), id];
}

function track() {
  return document.querySelector(".plot-track");
}

function mark(id) {
  $("plots").dataset.inView = id;
  for (const button of document.querySelectorAll(".plot-picker button")) {
    button.setAttribute("aria-pressed", String(button.dataset.show === id));
  }
}

/** True in the phone's layout (the plots stay at the top of the screen). */
export function onPhone() {
  return PHONE.matches;
}

/** Bring plot `id` into view (on a phone). */
export function showPlotInView(id, behavior = "smooth") {
  if (!PHONE.matches) return;
  const strip = track();
  const card = $(`card-${id}`);
  mark(id);
  strip.scrollTo({ left: card.offsetLeft - strip.offsetLeft, behavior });
}

/** The plot a swipe left in view: the card nearest the strip's left edge. */
function inView() {
  const strip = track();
  const cards = [...strip.children];
  const left = strip.scrollLeft + strip.offsetLeft;
  const nearest = cards.reduce((best, card) => (
    Math.abs(card.offsetLeft - left) < Math.abs(best.offsetLeft - left) ? card : best));
  return nearest.id.replace(/^card-/, "");
}

function followControl(event) {
  const name = event.target?.dataset?.param ?? event.target?.id;
  const plots = Object.hasOwn(PLOTS_OF, name) ? PLOTS_OF[name] : null;
  if (!PHONE.matches || !plots) return;
  const current = $("plots").dataset.inView;
  if (!plots.includes(current)) showPlotInView(plots[0], "instant");
}

export function initPhone() {
  mark("stribeck");
  for (const button of document.querySelectorAll(".plot-picker button")) {
    button.addEventListener("click", () => showPlotInView(button.dataset.show));
  }
  track().addEventListener("scrollend", () => {
    if (PHONE.matches) mark(inView());
  });
  const controls = $("controls");
  controls.addEventListener("focusin", followControl);
  controls.addEventListener("pointerdown", followControl);
  // a layout that changes (a phone turned) keeps the plot that was in view
  PHONE.addEventListener("change", () => showPlotInView($("plots").dataset.inView, "instant"));
  // what is scrolled or tabbed to comes into view below the plots, not under them
  new ResizeObserver(() => {
    document.documentElement.style.scrollPaddingTop = PHONE.matches
      ? `${Math.ceil($("plots").getBoundingClientRect().height) + 8}px` : "";
  }).observe($("plots"));
}
