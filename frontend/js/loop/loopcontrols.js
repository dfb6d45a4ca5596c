// The control loop's controls: a labelled slider and number box per number of
// loopstate.js's table (built as controls.js builds the friction's), the reference,
// compensation and compensator menus and the force limit. Each changes `app.state` and
// hands it to the render path like the friction's controls do: a moving slider draws
// live, a released one is a history entry. A number typed that may not be used shows
// its error and is not taken.

import {
  buildControl, paramList, parseNumber, registerControlWriter, roundSignificant,
  sliderToValue, valueToSlider,
} from "../page/controls.js";
import { wireSliderKeys } from "../page/inputs.js";
import {
  COMP_PARAMS, LOOP_CONTROLS, compParams, loopError, loopSpec,
} from "./loopstate.js";
import { refresh, settleNow } from "../page/render.js";
import {
  $, app, commit, setAttr, setHidden, setText,
} from "../page/store.js";

/** Where each slider goes in the loop's fieldset. */
const HOSTS = {
  Kp: "gains", Ki: "gains", Kd: "gains", m_loop: "gains", h: "reference", w: "reference",
  f: "reference", c: "compensation", u_max: "limit",
};

/** Written at every move of any slider (the friction's too): only what changes is
 *  written, each write making the browser check the page's styles again. */
function showError(name, message) {
  const error = $(`${name}-error`);
  setText(error, message ?? "");
  setHidden(error, !message);
  setAttr($(name), "aria-invalid", message ? "true" : "false");
  $(name).closest(".control").classList.toggle("invalid", Boolean(message));
}

/** Show the controls the state uses (a ramp has no h, a sine has f, …). */
function showUsed(state) {
  for (const spec of LOOP_CONTROLS) {
    if (spec.when) setHidden($(spec.name).closest(".control"), !spec.when(state));
  }
  const fitted = Boolean(compParams(state));
  $("loop-comp-model").querySelector('option[value="fitted"]').disabled = !fitted;
  setHidden($("loop-comp-model").closest(".control"), state.comp === "off");
  setText($("loop-comp-model-note"), fitted
    ? `the fitted model: ${paramList(COMP_PARAMS, state, { values: compParams(state) })}`
    : "a fitted model comes from the data panel (Try this model in a control loop)");
}

/** Write the loop's part of `state` into its controls (all but `except`). */
export function writeLoopControls(state, except = null) {
  for (const spec of LOOP_CONTROLS) {
    const box = $(spec.name);
    const range = $(`${spec.name}-range`);
    if (box !== except) box.value = String(roundSignificant(Number(state[spec.name]), 6));
    if (range !== except) range.value = String(valueToSlider(spec, Number(state[spec.name])));
    if (box !== except) showError(spec.name, null);
  }
  $("loop-ref").value = state.ref;
  $("loop-comp").value = state.comp;
  $("loop-comp-model").value = state.comp_model;
  $("loop-limit").checked = Boolean(state.limit);
  showUsed(state);
}

/** Widen a slider's range by decades to hold `value` (a fitted model's scale). */
export function widenLoopRange(name, value) {
  const spec = loopSpec(name);
  if (!spec || spec.scale === "linear" || !(value > 0)) return;
  if (value < spec.min) spec.min = 10 ** Math.floor(Math.log10(value / 10));
  if (value > spec.max) spec.max = 10 ** Math.ceil(Math.log10(value * 10));
}

/** The states one key press away on `spec`'s slider (asked for ahead). */
function neighbours(spec, range) {
  const out = [];
  for (const step of [-1, 1]) {
    const position = Number(range.value) + step;
    if (position < Number(range.min) || position > Number(range.max)) continue;
    const value = sliderToValue(spec, position);
    if (!loopError(spec.name, value)) out.push({ ...app.state, [spec.name]: value });
  }
  return out;
}

function wireSlider(spec) {
  const box = $(spec.name);
  const range = $(`${spec.name}-range`);
  const moved = () => {
    const value = sliderToValue(spec, range.value);
    if (loopError(spec.name, value)) return; // a sine's f past the run's periods
    app.state[spec.name] = value;
    box.value = String(value);
    showError(spec.name, null);
    refresh({ hold: true });
  };
  range.addEventListener("input", moved);
  wireSliderKeys(range, moved, () => neighbours(spec, range));
  box.addEventListener("input", () => {
    const value = parseNumber(box.value);
    const message = loopError(spec.name, value);
    showError(spec.name, message);
    if (message) return;
    app.state[spec.name] = value;
    range.value = String(valueToSlider(spec, value));
    refresh({ hold: true });
  });
  for (const control of [range, box]) {
    control.addEventListener("change", () => {
      commit();
      settleNow();
    });
  }
}

/** A menu or the check box changed the state: drawn at once, one history entry. */
function chose(name, value) {
  app.state[name] = value;
  showUsed(app.state);
  commit();
  refresh();
}

/** Build the loop's controls into its fieldset and wire them. */
export function buildLoopControls() {
  for (const spec of LOOP_CONTROLS) {
    $(`controls-loop-${HOSTS[spec.name]}`).append(buildControl(spec));
    wireSlider(spec);
  }
  $("loop-ref").addEventListener("change", () => chose("ref", $("loop-ref").value));
  $("loop-comp").addEventListener("change", () => chose("comp", $("loop-comp").value));
  $("loop-comp-model").addEventListener("change", () => chose("comp_model", $("loop-comp-model").value));
  $("loop-limit").addEventListener("change", () => chose("limit", $("loop-limit").checked));
  registerControlWriter(writeLoopControls);
}
