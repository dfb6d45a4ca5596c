// The control loop's part of the explorer's state (a PID position loop on the model's
// friction): its controls' table, its defaults (the server's params.LOOP_DEFAULTS,
// echoed by POST /api/loop {}), its round trip through the URL, and the body of
// POST /api/loop. Pure but for loadLoopDefaults. The friction comes from the explorer's sliders (Fc, Fs, V, δ, σ, s, z*, F̂);
// the mass is the loop's own `m_loop`: the ramp's default m = 1e-4 kg with the loop's
// default gains makes the linear loop unstable (Kd·Kp = 9e-5 < m·Ki = 3e-4 N²·s/m²).

import { parseNumber, roundSignificant } from "../page/controls.js";
import { LOOP_SERIES } from "../models/loopmodel.js";

/** The loop's sliders, in the order of the form: the table controls.js's sliders use
 *  (named: the label's words, symbol, unit: linear, in the state's units on the page;
 *  scale log, log0 with 0 at the left end, or linear with step). `when`: the state in
 *  which the control shows (the reference's kind, the compensation, the limit). */
export const LOOP_CONTROLS = [
  { name: "Kp", named: "Kp", symbol: "Kp", unit: "N/m", help: "proportional gain, ≥ 0",
    scale: "log", min: 1e-3, max: 1 },
  { name: "Ki", named: "Ki", symbol: "Ki", unit: "N/(m·s)",
    help: "integral gain, ≥ 0 (slider's left end is 0: no integral action)", scale: "log0", min: 0.01, max: 100 },
  { name: "Kd", named: "Kd", symbol: "Kd", unit: "N·s/m",
    help: "derivative gain on ṙ − ẋ (no kick at a step), ≥ 0 (left end 0)", scale: "log0", min: 1e-4, max: 0.1 },
  { name: "m_loop", named: "Loop mass (m_loop)", symbol: "m_loop", unit: "kg",
    help: "the loop's moving mass, > 0 (its own: the ramp's m with these gains is unstable)",
    scale: "log", min: 1e-6, max: 1e-2 },
  { name: "h", named: "Reference size h", symbol: "h", unit: "m", help: "the step's height, or the sine's amplitude, > 0",
    scale: "log", min: 0.1, max: 1000, when: (state) => state.ref !== "ramp" },
  { name: "w", named: "Ramp speed w", symbol: "w", unit: "m/s", help: "the ramp's speed from rest, > 0",
    scale: "log", min: 0.1, max: 1000, when: (state) => state.ref === "ramp" },
  { name: "f", named: "Sine frequency f", symbol: "f", unit: "Hz", help: "the sine's frequency, > 0",
    scale: "log", min: 0.02, max: 10, when: (state) => state.ref === "sine" },
  { name: "c", named: "Compensation scale c", symbol: "c", unit: "", help: "u gets c·Fss(ṙ): 1 is exact, ≥ 0",
    scale: "linear", min: 0, max: 2, step: 0.05, when: (state) => state.comp === "scaled" },
  { name: "u_max", named: "Force limit u_max", symbol: "u_max", unit: "N",
    help: "|u| ≤ u_max, > 0; the integrator winds up meanwhile", scale: "log", min: 0.1, max: 100,
    when: (state) => state.limit },
];

export const REFERENCES = ["step", "ramp", "sine"];
export const COMPENSATIONS = ["off", "exact", "scaled"];
/** The compensator's model: the plant's (the friction sliders) or a fitted one. */
export const COMP_MODELS = ["plant", "fitted"];
/** The friction parameters of a compensator's own model, as URL keys cFc, cFs, … */
export const COMP_PARAMS = ["Fc", "Fs", "V", "delta", "sigma"];
const NUMBERS = LOOP_CONTROLS.map((spec) => spec.name);
/** Of the loop's numbers, those that may be 0 (the gains and c); the rest must be > 0. */
const ZERO_OK = new Set(["Kp", "Ki", "Kd", "c"]);
/** At most this many sine periods in a run (the server's limit). */
const MAX_SINE_PERIODS = 200;

/** The page's own starting values where the server has none: the scale c once
 *  "scaled" is chosen, and the limit once switched on (above the default loop's
 *  break-away force, 1.45 N, so that the loop still moves). */
const PAGE_DEFAULTS = { comp: "off", c: 0.5, limit: false, u_max: 2, comp_model: "plant" };

let defaults = null; // the loop part of a default state, once loadLoopDefaults has run
let duration = 5; // [s], the server's LOOP_COMMON
let reference = null; // the server's default reference sizes {h, w, f}
/** Samples of a run's uniform grid the page asks for (the server's default). */
const POINTS = 2000;

/** The loop's defaults from the server: POST /api/loop {} echoes them (a short grid). */
export async function loadLoopDefaults(postJSON) {
  const echo = await postJSON("/api/loop", { points: 10 });
  duration = echo.duration;
  reference = { h: echo.reference.h, w: echo.reference.w, f: echo.reference.f };
  defaults = {
    Kp: echo.controller.Kp, Ki: echo.controller.Ki, Kd: echo.controller.Kd,
    m_loop: echo.params.m, ref: echo.reference.kind,
    h: echo.reference.h, w: echo.reference.w, f: echo.reference.f,
    ...PAGE_DEFAULTS,
    cFc: null, cFs: null, cV: null, cdelta: null, csigma: null,
  };
  return defaults;
}

export function loopDefaults() {
  return { ...defaults };
}

/** The run's length [s]. */
export function loopDuration() {
  return duration;
}

/** The spec of a loop slider. */
export function loopSpec(name) {
  return LOOP_CONTROLS.find((spec) => spec.name === name);
}

/** The message for a loop number that may not be used, or null. */
export function loopError(name, value) {
  if (Number.isNaN(value)) return `${name} must be a number`;
  if (ZERO_OK.has(name) ? value < 0 : !(value > 0)) return `${name} must be ${ZERO_OK.has(name) ? "≥" : ">"} 0`;
  if (name === "f" && value * duration > MAX_SINE_PERIODS) {
    return `f must be ≤ ${MAX_SINE_PERIODS / duration} Hz (${MAX_SINE_PERIODS} periods in ${duration} s)`;
  }
  return null;
}

/** The compensator's own model in `state`, or null when it has none (all five set). */
export function compParams(state) {
  const values = Object.fromEntries(COMP_PARAMS.map((name) => [name, state[`c${name}`]]));
  return Object.values(values).every(Number.isFinite) ? values : null;
}

/** Read the loop's keys from a query string into `state` (a bad value keeps the default). */
export function readLoop(query, state) {
  for (const name of [...NUMBERS, ...COMP_PARAMS.map((p) => `c${p}`)]) {
    if (!query.has(name)) continue;
    const value = parseNumber(query.get(name));
    if (name.startsWith("c") && name !== "c" ? Number.isFinite(value) : !loopError(name, value)) {
      state[name] = value;
    }
  }
  const pick = (name, choices) => {
    if (choices.includes(query.get(name))) state[name] = query.get(name);
  };
  pick("ref", REFERENCES);
  pick("comp", COMPENSATIONS);
  pick("comp_model", COMP_MODELS);
  if (query.has("limit")) state.limit = query.get("limit") === "1";
  if (state.comp_model === "fitted" && !compParams(state)) state.comp_model = "plant";
}

/** Write the loop's keys of `state` into a query string (the compensator's own model
 *  only when it has one). */
export function writeLoop(state, query) {
  for (const name of NUMBERS) query.set(name, String(state[name]));
  query.set("ref", state.ref);
  query.set("comp", state.comp);
  query.set("limit", state.limit ? "1" : "0");
  query.set("comp_model", state.comp_model);
  if (compParams(state)) {
    for (const name of COMP_PARAMS) query.set(`c${name}`, String(state[`c${name}`]));
  }
}

/** The compensation's scale c in `state`. */
export function compScale(state) {
  return { off: 0, exact: 1, scaled: Number(state.c) }[state.comp] ?? 0;
}

/** The body of POST /api/loop for a valid state: the explorer's friction, the loop's
 *  mass, gains and reference (only what its kind uses, so that a hidden slider asks for
 *  nothing), the compensation (its own model when chosen). */
export function loopBody(state) {
  const body = { model: "presliding", F_hat: state.F_hat, m: Number(state.m_loop), points: POINTS };
  for (const name of ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba"]) body[name] = parseNumber(state[name]);
  body.controller = {
    Kp: Number(state.Kp), Ki: Number(state.Ki), Kd: Number(state.Kd),
    u_max: state.limit ? Number(state.u_max) : null,
  };
  const kind = state.ref;
  body.reference = kind === "ramp" ? { kind, w: Number(state.w) }
    : kind === "sine" ? { kind, h: Number(state.h), f: Number(state.f) } : { kind, h: Number(state.h) };
  const scale = compScale(state);
  body.compensation = { scale };
  const own = compParams(state);
  if (scale > 0 && state.comp_model === "fitted" && own) body.compensation.params = own;
  return body;
}

let worker = null; // the worker, once started; false once it failed (the server runs all)
const pending = new Map(); // run id -> its promise's resolve
let runs = 0;

/** The run of `body` made in the page (loopmodel.js, the server's model and integrator,
 *  in loopworker.js off the main thread), the reference's missing sizes the server's:
 *  a promise of the answer, or of null when it is the server's to make. */
export function localLoop(body) {
  if (worker === false) return Promise.resolve(null);
  if (!worker) {
    worker = new Worker(new URL("../models/loopworker.js", import.meta.url), { type: "module" });
    worker.onmessage = ({ data: { id, result } }) => {
      // the series as the server's answer has them: plain arrays
      for (const name of result ? LOOP_SERIES : []) result[name] = Array.from(result[name]);
      pending.get(id)?.(result);
      pending.delete(id);
    };
    worker.onerror = () => { // it did not start: the server makes every run from now on
      worker.terminate();
      worker = false;
      for (const resolve of pending.values()) resolve(null);
      pending.clear();
    };
  }
  runs += 1;
  const id = runs;
  return new Promise((resolve) => {
    pending.set(id, resolve);
    worker.postMessage({ id, body, defaults: { ...reference, duration } });
  });
}

/** Round up to two significant digits (a gain the sentence proposes). */
export function niceUp(value) {
  if (!(value > 0)) return value;
  const unit = 10 ** (Math.floor(Math.log10(value)) - 1);
  return roundSignificant(Math.ceil(value / unit - 1e-9) * unit, 2);
}

/**
 * The loop's part of a state for a fitted model `values` ({Fc, Fs, V, delta, sigma, s?})
 * tried in the loop. `compensatorOnly`: the plant keeps the sliders and the compensator
 * takes the fitted model (exact compensation if it was off). Otherwise the plant takes
 * the fitted model and the loop's defaults are carried to its scales, so that it is as
 * strong against this friction as the defaults are against the explorer's: forces ×
 * Fs/Fs₀, lengths × s₀/s (Fs₀, s₀ the explorer's defaults), time kept (Kp, Ki, Kd and
 * the mass × force/length, h and w × length, u_max × force).
 */
export function fittedLoopState(values, state, explorerDefaults, compensatorOnly) {
  if (compensatorOnly) {
    const own = Object.fromEntries(COMP_PARAMS.map((name) => [`c${name}`, values[name] ?? 0]));
    return { ...own, comp_model: "fitted", comp: state.comp === "off" ? "exact" : state.comp };
  }
  const force = values.Fs / explorerDefaults.Fs;
  const length = explorerDefaults.s / Number(values.s ?? state.s);
  const scaled = (value, factor) => roundSignificant(value * factor, 4);
  return {
    Kp: scaled(defaults.Kp, force / length), Ki: scaled(defaults.Ki, force / length),
    Kd: scaled(defaults.Kd, force / length), m_loop: scaled(defaults.m_loop, force / length),
    h: scaled(defaults.h, length), w: scaled(defaults.w, length),
    u_max: scaled(PAGE_DEFAULTS.u_max, force), comp_model: "plant",
  };
}
