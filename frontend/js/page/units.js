// The units every label, axis, tooltip, sentence, table and export of the page is
// written in, from one place. The model holds in any consistent units: the explorer's
// are linear (N, m) until the parameters of a fit of rotary data are used (N·m, and
// rad or deg, the data's own), and a preset in SI units returns them to linear. The
// state names them (`state.units`, in the URL when not linear).
//
// A quantity names its linear unit, as the server's parameter table does ("N·s/m");
// `unit(linear, state)` gives it in the state's units, as the server's fit report gives
// rotary data's (identify/csvdata unit_of: N → N·m, m → rad, kg → kg·m², …).
// Static text of the page marks its units <span data-unit="N/s">N/s</span>, and
// `writeUnits` writes them in the state's units.

/** The unit systems a state may be in. */
export const UNIT_SYSTEMS = ["linear", "rotary", "rotary-deg"];

/** Linear units and their rotary counterparts (positions in rad); the server's table
 *  (csvdata.dataset._ROTARY_UNIT) and the control loop's gains. */
const ROTARY = {
  "N·s/m": "N·m·s/rad", "m/s": "rad/s", "1/m": "1/rad", kg: "kg·m²", N: "N·m", m: "rad",
  "m/s²": "rad/s²", "N/s": "N·m/s", "N·(s/m)^n": "N·m·(s/rad)^n",
  "N/m": "N·m/rad", "N/(m·s)": "N·m/(rad·s)", "N²·s/m²": "(N·m)²·s/rad²",
};

/** The unit system of `state` ("linear" when it names none). */
export function unitsOf(state) {
  return UNIT_SYSTEMS.includes(state?.units) ? state.units : "linear";
}

/** The unit `linear` (a linear SI unit, "" for none) in the units of `state`. */
export function unit(linear, state) {
  const system = unitsOf(state);
  if (system === "linear" || !linear) return linear;
  const rotary = ROTARY[linear] ?? linear;
  if (system === "rotary") return rotary;
  // positions in degrees: every unit with an angle in it follows; an inertia is then
  // a torque per angular acceleration
  return rotary === "kg·m²" ? "N·m·s²/deg" : rotary.replaceAll("rad", "deg");
}

/** The unit system of a fit report's data (its `units`: F in N·m for rotary data, x in
 *  deg when the positions are). */
export function unitsOfReport(report) {
  const units = report?.units ?? {};
  const force = units.F ?? units.F_ba ?? "N";
  if (!force.startsWith("N·m")) return "linear";
  return units.x === "deg" ? "rotary-deg" : "rotary";
}

/** A number to `digits` significant digits, as the sentences quote them. */
export function fmt(value, digits = 3) {
  if (value == null || !Number.isFinite(value)) return "–";
  return String(Number(value.toPrecision(digits)));
}

/** "1.45 N·m": a value with its unit in the state's units. */
export function quantity(value, linear, state, digits = 3) {
  const shown = unit(linear, state);
  return shown ? `${fmt(value, digits)} ${shown}` : fmt(value, digits);
}

/** "symbol [unit]" in the state's units, or the symbol alone for a pure number. */
export function label(symbol, linear, state) {
  const shown = unit(linear, state);
  return shown ? `${symbol} [${shown}]` : symbol;
}

/** Plotly's hover part "name = %{x:.3g} unit" in the state's units. */
export function hover(name, variable, format, linear, state) {
  const shown = unit(linear, state);
  return `${name} = %{${variable}:${format}}${shown ? ` ${shown}` : ""}`;
}

let written = null; // the unit system the page's marked text was last written in

/** Write every marked unit of the page (data-unit) in the units of `state`. */
export function writeUnits(state, root = document) {
  const system = unitsOf(state);
  if (system === written) return;
  written = system;
  for (const element of root.querySelectorAll("[data-unit]")) {
    element.textContent = unit(element.dataset.unit, state);
  }
}
