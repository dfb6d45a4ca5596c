// A finished fit shown: its units, summary, tables, steps, plan and figures; its plots'
// exports, its report and residuals for download, and its parameters handed to the
// explorer.

import { paramList } from "../page/controls.js";
import { unit, unitsOfReport } from "../page/units.js";
import { drawFigure } from "../plots/draw.js";
import { download } from "../plots/export.js";
import { residualsCsv } from "./fitjob.js";
import { showFitOutputs } from "./fitoutputs.js";
import { explorerParams, measuredOverlay } from "./fitparams.js";
import { fitFigures, formatNumber, modelCaption } from "./fitplots.js";
import {
  plotCard, renderErrorTable, renderParamTable, renderSteps, renderSummary,
} from "./fitview.js";
import { $, panel, showError } from "./panelstate.js";
import { clearPlan, drawPlanFigure, showPlan } from "./plan.js";
import { endQuiz, quizPending } from "./quiz.js";

export function clearResults() {
  panel.result = null;
  endQuiz();
  const results = $("fit-results");
  results.hidden = true;
  for (const div of results.querySelectorAll(".fit-plot")) {
    if (window.Plotly && div.data) window.Plotly.purge(div);
  }
  panel.figures = null;
  $("fit-effect-plots").replaceChildren();
  $("use-note").textContent = "";
  clearPlan();
}

/** The units the page's static text names for a report (data-report-unit): its data's
 *  (rotary data in N·m and rad); the force of break-away data is F_ba's. */
function writeReportUnits(report) {
  const units = { ...report.units, F: report.units?.[report.kind === "breakaway" ? "F_ba" : "F"] };
  const system = { units: unitsOfReport(report) };
  for (const element of document.querySelectorAll("[data-report-unit]")) {
    // the page's text holds the linear unit (a steady report has no s of its own)
    element.dataset.linear ??= element.textContent;
    element.textContent = units[element.dataset.reportUnit] ?? unit(element.dataset.linear, system);
  }
}

export async function showResults(job) {
  const report = job.report;
  writeReportUnits(report);
  renderSummary(job);
  showFitOutputs(report, panel.explorerS());
  renderErrorTable(report);
  renderParamTable(report);
  renderSteps(report);
  showPlan(report);
  const figures = fitFigures(job);
  $("fit-model-caption").textContent = modelCaption(report.kind);
  if (quizPending()) {
    // before the reveal: the data, the base model and its residual only
    figures.model.data = figures.model.data.filter((t) => t.name !== "final model");
    if (figures.time) figures.time.data = figures.time.data.filter((t) => t.name !== "final model");
    figures.residual.data = figures.residual.data.filter((t) => !t.name.startsWith("after"));
    figures.effects = [];
  }
  const effectPlots = $("fit-effect-plots");
  effectPlots.replaceChildren(...figures.effects.map(({ effect, regressor }) => plotCard(
    `fit-plot-effect-${effect}`, `fit-effect-${effect}`, `${effect}: residual against ${regressor}`,
    `Where ${effect} showed: the residual against ${regressor} before (grey) and after (blue).`)));
  $("fit-time-card").hidden = !figures.time;
  $("fit-results").hidden = false; // visible before drawing, so the plots take their size
  panel.figures = figures;
  await drawFitFigures();
}

/** The fit's figures as the page is shown now (again when its style changes). */
export function drawFitFigures() {
  const figures = panel.figures;
  if (!figures || $("fit-results").hidden) return Promise.resolve();
  return Promise.all([
    drawPlanFigure(),
    drawFigure($("fit-plot-model"), figures.model),
    ...(figures.time ? [drawFigure($("fit-plot-time"), figures.time)] : []),
    drawFigure($("fit-plot-residual"), figures.residual),
    ...figures.effects.map(({ effect, figure }) => drawFigure($(`fit-plot-effect-${effect}`), figure)),
  ]);
}

/** What an export of one of the fit's plots needs (export.js): its figure, its title
 *  and a caption of the data and the final model's parameters in the data's units. */
export function describeFitPlot(plot) {
  const job = panel.result;
  const figures = panel.figures;
  if (!job || !figures) return null;
  const effect = plot.startsWith("fit-effect-") ? plot.slice("fit-effect-".length) : null;
  const figure = effect ? figures.effects.find((entry) => entry.effect === effect)?.figure
    : { "fit-model": figures.model, "fit-time": figures.time, "fit-residual": figures.residual }[plot];
  if (!figure) return null;
  const report = job.report;
  const params = Object.entries(report.final.params).map(([name, value]) => {
    const shown = report.units?.[name];
    return `${name} = ${formatNumber(value, 4)}${shown && shown !== "-" ? ` ${shown}` : ""}`;
  });
  const effects = report.effects.length ? report.effects.join(", ") : "none";
  return {
    name: `${stem(job)}-${plot}`,
    title: document.querySelector(`[data-plot="${plot}"]`).closest(".plot-card").querySelector("h3").textContent,
    caption: `${job.source}: ${report.kind}, ${report.n} rows; effects found: ${effects}; final model: ${params.join(", ")}`,
    figure,
  };
}

function stem(job) {
  return (job.source || "data").replace(/\.[^.]*$/, "").replace(/[^\w.-]+/g, "_") || "data";
}

export function downloadReport() {
  const job = panel.result;
  if (!job) return;
  const text = `${JSON.stringify(job.report, null, 2)}\n`;
  download(`${stem(job)}-report.json`, new Blob([text], { type: "application/json" }));
}

export async function downloadResiduals() {
  const job = panel.result;
  if (!job) return;
  try {
    const text = await residualsCsv(job.id).catch((error) => {
      throw new Error(`HTTP ${error.status}: the server no longer holds this fit; fit again`);
    });
    download(`${stem(job)}-residuals.csv`, new Blob([text], { type: "text/csv" }));
  } catch (error) {
    showError(`The residuals could not be downloaded: ${error.message}`);
  }
}

export function useParameters() {
  const job = panel.result;
  if (!job || !panel.applyParams) return;
  const { values, notes, ranges, units } = explorerParams(job.report);
  const state = panel.applyParams(values, { ranges, measured: measuredOverlay(job), units });
  $("use-note").textContent = state === false
    ? "The explorer is not ready yet; try again in a moment."
    : `Set ${paramList(Object.keys(values), state)}.${notes.length ? ` Note: ${notes.join("; ")}.` : ""}`;
}
