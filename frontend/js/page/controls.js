// The parameter controls: one labelled slider and one labelled number box per parameter,
// labelled in the state's units (units.js), slider <-> value maps (logarithmic where a
// range spans decades), and the model's constraints that decide whether a state may be
// sent at all.

import { F_HAT_CHOICES } from "../models/model.js";
import { setPresentation } from "../plots/draw.js";
import { setAttr, setHidden, setText } from "./store.js";
import {
  fmt, label, unit, unitsOf, writeUnits,
} from "./units.js";

const STEPS = 1000; // slider positions of a log or linear control

/**
 * The numeric parameters, in the order of the form: filled from the server's one table
 * (GET /api/presets → parameters) by setParams before the controls are built. Each:
 * {name, symbol, unit (linear), named ("symbol (name)"), help, group (the fieldset),
 * scale, min, max, step?}.
 */
export const PARAMS = [];

/** Fill PARAMS from the server's table. */
export function setParams(table) {
  PARAMS.splice(0, PARAMS.length, ...table.map((row) => (
    { ...row, named: row.symbol === row.name ? row.symbol : `${row.symbol} (${row.name})` })));
}

/** A control's label in the state's units: "named [unit]" ("Fc [N·m]", "δ (delta)"). */
export function controlLabel(spec, state) {
  return label(spec.named, spec.unit, state);
}

/** "Fc = 1 N, V = 100 m/s, δ = 1": parameters `names` of `state` (or their `values`)
 *  with their units in the state's (a control's spec, of the friction's or the loop's
 *  table, found by `specOf`). */
export function paramList(names, state, { values = state, specOf = paramSpec } = {}) {
  return names.map((name) => {
    const spec = specOf(name);
    const value = Number(values[name]);
    const shown = unit(spec?.unit ?? "", state);
    return `${spec?.symbol ?? name} = ${fmt(value, 4)}${shown ? ` ${shown}` : ""}`;
  }).join(", ");
}

/** The PARAMS row of a parameter (undefined for a name without a control). */
export function paramSpec(name) {
  return PARAMS.find((spec) => spec.name === name);
}

export const MIN_ABS_DELTA = 0.05;

/** Round to `digits` significant digits (what a slider move writes into the box). */
export function roundSignificant(value, digits = 4) {
  if (!Number.isFinite(value) || value === 0) return value;
  return Number(value.toPrecision(digits));
}

/** Values a linear slider skips: those with |value| below the gap (δ = 0 is no model,
 *  the model asks |δ| ≥ 0.05), so that every position the slider offers is valid. */
const SLIDER_GAPS = { delta: MIN_ABS_DELTA };

/** The raw steps (min + i·step) a linear slider skips: [first, count]. */
function skipped(spec) {
  const gap = SLIDER_GAPS[spec.name];
  if (spec.scale !== "linear" || !gap) return [Infinity, 0];
  const tolerance = 1e-9 * spec.step;
  const first = Math.max(0, Math.ceil((-gap + tolerance - spec.min) / spec.step));
  const last = Math.floor((gap - tolerance - spec.min) / spec.step);
  return last >= first ? [first, last - first + 1] : [Infinity, 0];
}

/** Value of slider position `pos` (0..STEPS, or `step` units for linear). */
export function sliderToValue(spec, pos) {
  const p = Number(pos);
  if (spec.scale === "linear") {
    const [first, count] = skipped(spec);
    return roundSignificant(spec.min + (p < first ? p : p + count) * spec.step, 6);
  }
  if (spec.scale === "log0" && p === 0) return 0;
  const lo = Math.log10(spec.min);
  const hi = Math.log10(spec.max);
  const first = spec.scale === "log0" ? 1 : 0;
  const fraction = (p - first) / (STEPS - first);
  return roundSignificant(10 ** (lo + fraction * (hi - lo)), 4);
}

/** Nearest slider position of `value` (clamped to the slider's range; a value in a gap
 *  goes to the gap's edge on its side). */
export function valueToSlider(spec, value) {
  if (spec.scale === "linear") {
    const [first, count] = skipped(spec);
    const raw = clamp(Math.round((value - spec.min) / spec.step), 0, Math.round((spec.max - spec.min) / spec.step));
    if (raw < first) return raw;
    if (raw < first + count) return value < 0 ? first - 1 : first;
    return raw - count;
  }
  if (spec.scale === "log0" && value <= 0) return 0;
  if (!(value > 0)) return 0;
  const lo = Math.log10(spec.min);
  const hi = Math.log10(spec.max);
  const first = spec.scale === "log0" ? 1 : 0;
  const fraction = (Math.log10(value) - lo) / (hi - lo);
  return clamp(Math.round(first + fraction * (STEPS - first)), first, STEPS);
}

function clamp(x, lo, hi) {
  return Math.min(hi, Math.max(lo, x));
}

function sliderMax(spec) {
  return spec.scale === "linear" ? Math.round((spec.max - spec.min) / spec.step) - skipped(spec)[1] : STEPS;
}

/** Parse what a person typed: a finite number, or NaN. */
export function parseNumber(text) {
  if (typeof text === "number") return text;
  const trimmed = String(text ?? "").trim();
  if (trimmed === "") return NaN;
  const value = Number(trimmed);
  return Number.isFinite(value) ? value : NaN;
}

/**
 * The model's constraints for a state: {name: message} for each broken one.
 * Pure; the server checks the same and answers 422 naming the field.
 */
export function validate(state) {
  const errors = {};
  const num = {};
  for (const spec of PARAMS) {
    const value = parseNumber(state[spec.name]);
    if (Number.isNaN(value)) errors[spec.name] = `${spec.name} must be a number`;
    num[spec.name] = value;
  }
  const positive = ["Fc", "Fs", "V", "s", "m", "k"];
  for (const name of positive) {
    if (!(name in errors) && !(num[name] > 0)) errors[name] = `${name} must be > 0`;
  }
  if (!("Fs" in errors) && !("Fc" in errors) && num.Fs < num.Fc) {
    errors.Fs = `Fs must be ≥ Fc (${num.Fc})`;
  }
  if (!("delta" in errors) && !(Math.abs(num.delta) >= MIN_ABS_DELTA)) {
    errors.delta = `δ must satisfy |δ| ≥ ${MIN_ABS_DELTA} (δ ≠ 0)`;
  }
  if (!("sigma" in errors) && num.sigma < 0) errors.sigma = "σ must be ≥ 0";
  if (!("z_ba" in errors) && !(num.z_ba > 0 && num.z_ba < 1)) {
    errors.z_ba = "z* must be in (0, 1)";
  }
  if (!F_HAT_CHOICES.includes(state.F_hat)) {
    errors.F_hat = `F̂ must be one of ${F_HAT_CHOICES.join(", ")}`;
  }
  return errors;
}

/** A view's caption (views.js): parameters `names` (and F̂ when `fHat`) in the state's
 *  units. */
export function captionOf(names, { fHat = false } = {}) {
  return (state) => `${paramList(names, state)}${fHat ? `, F̂ = ${state.F_hat}` : ""}`;
}

const built = []; // the specs of every control built, relabelled when the units change
const elements = new Map(); // parameter name -> {box, range, error, wrap} of its control

/** One labelled slider + number box for `spec` (the friction's and the loop's alike),
 *  with its help and the place for its error. */
export function buildControl(spec) {
  built.push(spec);
  const wrap = document.createElement("div");
  wrap.className = "control";
  wrap.dataset.param = spec.name;

  const label = document.createElement("label");
  label.htmlFor = spec.name;
  label.textContent = controlLabel(spec, null);

  const row = document.createElement("div");
  row.className = "control-row";

  const rangeLabel = document.createElement("label");
  rangeLabel.htmlFor = `${spec.name}-range`;
  rangeLabel.className = "visually-hidden";
  rangeLabel.textContent = `${controlLabel(spec, null)} slider`;

  const range = document.createElement("input");
  range.type = "range";
  range.id = `${spec.name}-range`;
  range.min = "0";
  range.max = String(sliderMax(spec));
  range.step = "1";
  range.dataset.param = spec.name;

  const box = document.createElement("input");
  box.type = "text";
  box.inputMode = "decimal";
  box.id = spec.name;
  box.name = spec.name;
  box.autocomplete = "off";
  box.spellcheck = false;
  box.dataset.param = spec.name;
  box.setAttribute("aria-describedby", `${spec.name}-help ${spec.name}-error`);

  const help = document.createElement("p");
  help.id = `${spec.name}-help`;
  help.className = "hint";
  help.textContent = spec.help;

  const error = document.createElement("p");
  error.id = `${spec.name}-error`;
  error.className = "error";
  error.setAttribute("role", "alert");
  error.hidden = true;

  row.append(rangeLabel, range, box);
  wrap.append(label, row, help, error);
  elements.set(spec.name, { box, range, error, wrap });
  return wrap;
}

/** Build the slider + number box of each parameter into its fieldset. */
export function buildControls(root = document) {
  for (const spec of PARAMS) root.getElementById(`controls-${spec.group}`).append(buildControl(spec));
}

/** Controls that views build of their own write a state too: fn(state, except). */
const writers = [];

export function registerControlWriter(fn) {
  writers.push(fn);
}

let labelledIn = "linear"; // the unit system the controls are labelled in

/** Every control's labels, and every element that names a control (data-label-of), in
 *  the units of `state`; the page's marked units too. */
function relabel(state) {
  writeUnits(state);
  if (unitsOf(state) === labelledIn) return;
  labelledIn = unitsOf(state);
  for (const spec of built) {
    const text = controlLabel(spec, state);
    const { box, range } = elements.get(spec.name);
    if (box?.labels[0]) box.labels[0].textContent = text;
    if (range?.labels[0]) range.labels[0].textContent = `${text} slider`;
    for (const element of document.querySelectorAll(`[data-label-of="${spec.name}"]`)) element.textContent = text;
  }
}

/** Write a state into the controls (slider positions follow valid numbers only). */
export function writeControls(state, { except = null } = {}) {
  relabel(state);
  for (const spec of PARAMS) {
    const { box, range } = elements.get(spec.name);
    const raw = state[spec.name];
    // at most 6 significant digits in the box (the state keeps the full value)
    if (box !== except) box.value = typeof raw === "number" ? String(roundSignificant(raw, 6)) : String(raw ?? "");
    const value = parseNumber(raw);
    if (range !== except && !Number.isNaN(value)) range.value = String(valueToSlider(spec, value));
  }
  const fHat = document.getElementById("F_hat");
  if (fHat !== except) fHat.value = state.F_hat;
  document.getElementById("sim").checked = Boolean(state.sim);
  document.getElementById("lugre").checked = Boolean(state.lugre);
  document.getElementById("present").checked = Boolean(state.present);
  setPresentation(Boolean(state.present));
  for (const write of writers) write(state, except);
}

/** Show each error under its control and mark the control invalid; clear the others. */
export function showErrors(errors) {
  for (const spec of PARAMS) {
    const message = errors[spec.name];
    const { box, range, error, wrap } = elements.get(spec.name);
    setText(error, message ?? "");
    setHidden(error, !message);
    setAttr(box, "aria-invalid", message ? "true" : "false");
    setAttr(range, "aria-invalid", message ? "true" : "false");
    wrap.classList.toggle("invalid", Boolean(message));
  }
}

/** `state` with `spec`'s slider at `position` (and Fs/Fc coupled); true when the other
 *  of Fs and Fc moved. */
export function moveSlider(state, spec, position) {
  state[spec.name] = sliderToValue(spec, position);
  return couple(state, spec.name);
}

/** Keep Fs ≥ Fc as the person edits one of them in `state`: the other follows
 *  (the model needs Fs ≥ Fc). True when it moved. */
export function couple(state, name) {
  const Fc = parseNumber(state.Fc);
  const Fs = parseNumber(state.Fs);
  if (!(Fc > 0 && Fs > 0) || Fs >= Fc) return false;
  if (name === "Fc") state.Fs = Fc;
  else if (name === "Fs") state.Fc = Fs;
  else return false;
  return true;
}
