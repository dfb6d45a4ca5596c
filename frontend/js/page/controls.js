// The parameter controls: one labelled slider and one labelled number box per parameter,
// slider <-> value maps (logarithmic where a range spans decades), and the checks of
// MODEL.md §1 that decide whether a state may be sent at all.

import { F_HAT_CHOICES } from "../models/model.js";

const STEPS = 1000; // slider positions of a log or linear control

/**
 * The numeric parameters, in the order of the form: filled from the server's one table
 * (GET /api/presets → parameters) by setParams before the controls are built. Each:
 * {name, symbol, unit, label, help, group (the fieldset), scale, min, max, step?}.
 */
export const PARAMS = [];

/** Fill PARAMS from the server's table; the label is "symbol (name) [unit]". */
export function setParams(table) {
  PARAMS.splice(0, PARAMS.length, ...table.map((row) => {
    const named = row.symbol === row.name ? row.symbol : `${row.symbol} (${row.name})`;
    return { ...row, label: row.unit ? `${named} [${row.unit}]` : named };
  }));
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

/** Value of slider position `pos` (0..STEPS, or `step` units for linear). */
export function sliderToValue(spec, pos) {
  const p = Number(pos);
  if (spec.scale === "linear") return roundSignificant(spec.min + p * spec.step, 6);
  if (spec.scale === "log0" && p === 0) return 0;
  const lo = Math.log10(spec.min);
  const hi = Math.log10(spec.max);
  const first = spec.scale === "log0" ? 1 : 0;
  const fraction = (p - first) / (STEPS - first);
  return roundSignificant(10 ** (lo + fraction * (hi - lo)), 4);
}

/** Nearest slider position of `value` (clamped to the slider's range). */
export function valueToSlider(spec, value) {
  if (spec.scale === "linear") {
    const positions = Math.round((spec.max - spec.min) / spec.step);
    return clamp(Math.round((value - spec.min) / spec.step), 0, positions);
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
  return spec.scale === "linear" ? Math.round((spec.max - spec.min) / spec.step) : STEPS;
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
 * The constraints of MODEL.md §1 for a state: {name: message} for each broken one.
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

/** Build the slider + number box of each parameter into its fieldset. */
export function buildControls(root = document) {
  for (const spec of PARAMS) {
    const host = root.getElementById(`controls-${spec.group}`);
    const wrap = document.createElement("div");
    wrap.className = "control";
    wrap.dataset.param = spec.name;

    const label = document.createElement("label");
    label.htmlFor = spec.name;
    label.textContent = spec.label;

    const row = document.createElement("div");
    row.className = "control-row";

    const rangeLabel = document.createElement("label");
    rangeLabel.htmlFor = `${spec.name}-range`;
    rangeLabel.className = "visually-hidden";
    rangeLabel.textContent = `${spec.label} slider`;

    const range = document.createElement("input");
    range.type = "range";
    range.id = `${spec.name}-range`;
    range.min = "0";
    range.max = String(sliderMax(spec));
    range.step = "1";
    range.dataset.param = spec.name;
    if (spec.scale !== "linear") range.dataset.scale = "log";

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
    host.append(wrap);
  }
}

/** Controls that views build of their own write a state too: fn(state, except). */
const writers = [];

export function registerControlWriter(fn) {
  writers.push(fn);
}

/** Write a state into the controls (slider positions follow valid numbers only). */
export function writeControls(state, { except = null } = {}) {
  for (const spec of PARAMS) {
    const box = document.getElementById(spec.name);
    const range = document.getElementById(`${spec.name}-range`);
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
  document.body.classList.toggle("present", Boolean(state.present));
  for (const write of writers) write(state, except);
}

/** Show each error under its control and mark the control invalid; clear the others. */
export function showErrors(errors) {
  for (const spec of PARAMS) {
    const message = errors[spec.name];
    const box = document.getElementById(spec.name);
    const range = document.getElementById(`${spec.name}-range`);
    const error = document.getElementById(`${spec.name}-error`);
    error.textContent = message ?? "";
    error.hidden = !message;
    box.setAttribute("aria-invalid", message ? "true" : "false");
    range.setAttribute("aria-invalid", message ? "true" : "false");
    box.closest(".control").classList.toggle("invalid", Boolean(message));
  }
}

/** `state` with `spec`'s slider at `position` (and Fs/Fc coupled); true when the other
 *  of Fs and Fc moved. */
export function moveSlider(state, spec, position) {
  state[spec.name] = sliderToValue(spec, position);
  return couple(state, spec.name);
}

/** Keep Fs ≥ Fc as the person edits one of them in `state`: the other follows
 *  (MODEL.md §1). True when it moved. */
export function couple(state, name) {
  const Fc = parseNumber(state.Fc);
  const Fs = parseNumber(state.Fs);
  if (!(Fc > 0 && Fs > 0) || Fs >= Fc) return false;
  if (name === "Fc") state.Fs = Fc;
  else if (name === "Fs") state.Fc = Fs;
  else return false;
  return true;
}
