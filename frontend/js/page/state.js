// The explorer's whole state, and its round trip through the URL's query string.
// A state is a plain object: the model parameters (numbers, or the text a person typed
// when it is not a number yet), F_hat, the toggles `sim`, `lugre` and `present`, the
// units the page is written in (units.js), and the parts that views keep of their own
// (registerStatePart).

import { PARAMS, parseNumber } from "./controls.js";
import { UNIT_SYSTEMS } from "./units.js";

/** The numeric parameters' names (PARAMS is filled from the server at start-up). */
function paramNames() {
  return PARAMS.map((spec) => spec.name);
}
export const TOGGLES = { sim: true, lugre: false, present: false };

/** State that a view keeps of its own (the control loop's gains, say), registered by its
 *  module before the page starts: {name, defaults() → {key: value}, read(query, state),
 *  write(state, query)}. A preset keeps it; Reset returns it to its defaults. */
const parts = [];

export function registerStatePart(part) {
  parts.push(part);
}

/** The defaults of the state part `name` ({} when there is none). */
export function partDefaults(name) {
  return parts.find((part) => part.name === name)?.defaults() ?? {};
}

/** A full state from the server's defaults (GET /api/presets → defaults). */
export function defaultState(defaults) {
  const state = { ...TOGGLES, units: "linear" };
  for (const name of paramNames()) state[name] = defaults[name];
  state.F_hat = defaults.F_hat;
  for (const part of parts) Object.assign(state, part.defaults());
  return state;
}

/** The state a preset gives, keeping the toggles of `current`, and its units unless the
 *  preset is in SI units (a normalised preset's numbers hold in any). */
export function presetState(preset, defaults, current) {
  const state = defaultState({ ...defaults, ...preset.params });
  for (const name of Object.keys(TOGGLES)) state[name] = current[name];
  state.units = preset.units === "SI" ? "linear" : current.units;
  for (const part of parts) {
    for (const name of Object.keys(part.defaults())) state[name] = current[name];
  }
  return state;
}

/** Query string of a state (numbers as typed, so a link reproduces the view exactly). */
export function toQuery(state) {
  const query = new URLSearchParams();
  for (const name of paramNames()) query.set(name, String(state[name]));
  query.set("F_hat", state.F_hat);
  query.set("sim", state.sim ? "1" : "0");
  query.set("lugre", state.lugre ? "1" : "0");
  if (state.present) query.set("present", "1");
  if (state.units !== "linear") query.set("units", state.units);
  for (const part of parts) part.write(state, query);
  return `?${query.toString()}`;
}

/** State from a query string; missing keys take the defaults, bad numbers stay as text. */
export function fromQuery(search, defaults) {
  const query = new URLSearchParams(search);
  const state = defaultState(defaults);
  for (const name of paramNames()) {
    if (!query.has(name)) continue;
    const text = query.get(name);
    const value = parseNumber(text);
    state[name] = Number.isNaN(value) ? text : value;
  }
  if (query.has("F_hat")) state.F_hat = query.get("F_hat");
  for (const name of Object.keys(TOGGLES)) {
    if (query.has(name)) state[name] = query.get(name) === "1";
  }
  if (UNIT_SYSTEMS.includes(query.get("units"))) state.units = query.get("units");
  for (const part of parts) part.read(query, state);
  return state;
}

/** Name of the preset whose parameters equal the state's, or "". */
export function matchingPreset(state, presets) {
  for (const preset of presets) {
    const same = paramNames().every((name) => parseNumber(state[name]) === preset.params[name])
      && state.F_hat === preset.params.F_hat;
    if (same) return preset.name;
  }
  return "";
}

/** Whether parameter `name` moves the quasi-static frame: all but the mass m, which
 *  only the ramp experiment uses (moving m asks for no new frame). */
function movesFrame(name) {
  return name !== "m";
}

/** The body of POST /api/explore for a valid state. */
export function exploreBody(state) {
  const body = { F_hat: state.F_hat };
  for (const name of paramNames()) {
    if (movesFrame(name)) body[name] = parseNumber(state[name]);
  }
  return body;
}

/** Integrator steps per rate the page asks for: the default preset's slowest Fig. 3
 *  ramp needs about 100,000; parameters far from the note's scale (a fitted damper in
 *  kN) would otherwise keep the simulator busy for tens of seconds. */
export const INTERACTIVE_STEPS = 300_000;

/** The body of POST /api/simulate (presliding model) for a valid state and rates. */
export function simulateBody(state, rates) {
  const body = { model: "presliding", k: rates, max_steps: INTERACTIVE_STEPS };
  for (const name of ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "m"]) {
    body[name] = parseNumber(state[name]);
  }
  return body;
}
