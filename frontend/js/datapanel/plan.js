// "Plan the next experiment" under a report that leaves parameters not determined:
// the rig's limits as fields (starting at what the record reached), POST /api/plan,
// and its answer shown: the design, the standard errors now and after as a plot, the
// notes, and the programme to download. A failed plan says what the server named.

import { postJSON } from "../page/api.js";
import { parseNumber } from "../page/controls.js";
import { unit, unitsOfReport } from "../page/units.js";
import { drawFigure } from "../plots/draw.js";
import { download } from "../plots/export.js";
import { element } from "./fitview.js";
import { designSentence, planFigure, planReport, symbol, undetermined } from "./planfigure.js";

const $ = (id) => document.getElementById(id);
/** The limit fields and the request keys they fill. */
const LIMITS = { "plan-u-max": "u_max", "plan-v-max": "v_max", "plan-v-min": "v_min",
  "plan-travel": "travel", "plan-duration": "duration", "plan-sample-rate": "sample_rate" };
/** Runs of a plan to start with (the server's default). */
const RUNS = 12;
const plan = { report: null, answer: null, source: "data", controller: null };

/** A number for the field: what the record reached, to 4 significant digits. */
function fieldValue(value) {
  return value == null || !Number.isFinite(value) ? "" : String(Number(value.toPrecision(4)));
}

/** The limit fields' labels in the record's units: the report's own, or those of its
 *  unit system where it names none (a record of break-away forces has no x). */
function setLabels(report) {
  const units = { units: unitsOfReport(report) };
  const named = (key, linear) => report.units?.[key] ?? unit(linear, units);
  const F = named("F", "N");
  const v = named("v", "m/s");
  $("plan-u-max-label").textContent = `Largest force u_max [${F}]`;
  $("plan-v-max-label").textContent = `Largest speed v_max [${v}]`;
  $("plan-v-min-label").textContent = `Slowest speed held v_min [${v}]`;
  $("plan-travel-label").textContent = `Travel [${named("x", "m")}]`;
  $("plan-noise-label").textContent = `Noise of one force [${F}]`;
  $("plan-s-low-label").textContent = `Presliding scale s at least [${named("s", "1/m")}]`;
  $("plan-s-high-label").textContent = `Presliding scale s at most [${named("s", "1/m")}]`;
}

/** The fields a family uses, the others hidden; the range of s where the record holds
 *  none (a steady curve) and the family needs it. */
function showFields() {
  const family = $("plan-family").value;
  for (const field of document.querySelectorAll("#plan-form .plan-field[data-family]")) {
    const families = field.dataset.family.split(" ");
    field.hidden = !families.includes(family)
      || (field.classList.contains("plan-s") && plan.report?.kind !== "steady");
  }
}

/** A new report: the section shown when it leaves parameters open, its fields filled
 *  with the record's extent. */
export function showPlan(report) {
  plan.report = report;
  plan.answer = null;
  $("plan-results").hidden = true;
  $("plan-error").hidden = true;
  const open = undetermined(report);
  $("plan-box").hidden = !open.length;
  if (!open.length) return;
  const extent = report.extent ?? {};
  $("plan-intro").textContent = `The data do not determine ${open.map(symbol).join(", ")}. `
    + "The plan proposes the runs, within your rig's limits, that determine them, and "
    + "predicts the standard errors after.";
  setLabels(report);
  const family = report.kind === "breakaway" ? "ramps" : report.kind === "steady" ? "steady" : "sine";
  $("plan-family").value = family;
  $("plan-runs").value = String(RUNS);
  $("plan-u-max").value = fieldValue(extent.force);
  $("plan-v-max").value = fieldValue(extent.speed);
  $("plan-v-min").value = fieldValue(report.kind === "steady" && extent.speeds
    ? extent.speeds[0] : extent.speed / 1000);
  $("plan-travel").value = fieldValue(extent.travel);
  $("plan-duration").value = fieldValue(extent.duration ?? 60);
  $("plan-sample-rate").value = fieldValue(extent.sample_rate ?? 1000);
  $("plan-noise").value = "";
  $("plan-s-low").value = "500";
  $("plan-s-high").value = "8000";
  showFields();
}

export function clearPlan() {
  plan.report = null;
  plan.answer = null;
  if (plan.controller) plan.controller.abort();
  $("plan-box").hidden = true;
  const div = $("plan-plot");
  if (window.Plotly && div.data) window.Plotly.purge(div);
}

/** The request of the form as it stands, or the name of the field that is not a number. */
function requestBody() {
  const family = $("plan-family").value;
  const body = { report: planReport(plan.report), family, limits: {} };
  const visible = (id) => !$(id).closest(".plan-field").hidden;
  for (const [id, key] of Object.entries(LIMITS)) {
    const text = $(id).value.trim();
    if (!visible(id) || text === "") continue;
    const value = parseNumber(text);
    if (!(value > 0)) return { bad: id };
    body.limits[key] = value;
  }
  if (visible("plan-runs")) {
    const runs = parseNumber($("plan-runs").value);
    if (!(Number.isInteger(runs) && runs >= 1)) return { bad: "plan-runs" };
    body.runs = runs;
  }
  if ($("plan-noise").value.trim() !== "") {
    const noise = parseNumber($("plan-noise").value);
    if (!(noise > 0)) return { bad: "plan-noise" };
    body.noise = noise;
  }
  if (visible("plan-s-low")) {
    const low = parseNumber($("plan-s-low").value);
    const high = parseNumber($("plan-s-high").value);
    if (!(low > 0)) return { bad: "plan-s-low" };
    if (!(high > low)) return { bad: "plan-s-high" };
    body.ranges = { s: [low, high] };
  }
  return { body };
}

function fail(message) {
  $("plan-error").textContent = message;
  $("plan-error").hidden = false;
}

async function makePlan(event) {
  event.preventDefault();
  if (!plan.report) return;
  $("plan-error").hidden = true;
  const { body, bad } = requestBody();
  if (bad) {
    const label = document.querySelector(`label[for="${bad}"]`)?.textContent ?? bad;
    fail(`The plan needs a number > 0 for “${label}”.`);
    $(bad).focus();
    return;
  }
  if (plan.controller) plan.controller.abort();
  const controller = new AbortController();
  plan.controller = controller;
  $("plan-start").disabled = true;
  $("plan-box").setAttribute("aria-busy", "true");
  try {
    const answer = await postJSON("/api/plan", body, controller.signal);
    if (controller !== plan.controller) return;
    plan.answer = answer;
    await showAnswer(answer);
  } catch (error) {
    if (error.name === "AbortError") return;
    const item = error.detail?.[0];
    const where = (item?.loc ?? []).filter((part) => part !== "body").join(".");
    fail(`No plan: ${error.message}${where ? ` (at ${where})` : ""}.`);
  } finally {
    if (controller === plan.controller) {
      $("plan-start").disabled = false;
      $("plan-box").removeAttribute("aria-busy");
      plan.controller = null;
    }
  }
}

async function showAnswer(answer) {
  $("plan-design").textContent = designSentence(answer);
  $("plan-notes").replaceChildren(...answer.notes.map((note) => element("li", { text: note })));
  $("plan-download").disabled = !answer.design;
  $("plan-results").hidden = false; // visible before drawing, so the plot takes its size
  await drawPlanFigure();
}

/** The plan's figure as the page is shown now (again when its style changes). */
export function drawPlanFigure() {
  if (!plan.answer || $("plan-results").hidden) return Promise.resolve();
  return drawFigure($("plan-plot"), planFigure(plan.answer, plan.report));
}

function downloadProgramme() {
  if (!plan.answer?.design) return;
  download(`plan-${plan.answer.family}.csv`, new Blob([plan.answer.programme], { type: "text/csv" }));
}

export function wirePlan() {
  $("plan-form").addEventListener("submit", makePlan);
  $("plan-family").addEventListener("change", showFields);
  $("plan-download").addEventListener("click", downloadProgramme);
}
