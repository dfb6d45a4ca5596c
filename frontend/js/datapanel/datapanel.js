// The data panel: upload measured data (file picker, drag and drop, or a bundled
// sample), fit it as a background job, and show the fit, the residuals, the diagnosis
// and the error before and after.
//
// One fit at a time from the page: starting a new one cancels the old. The job's
// requests (submit, poll, cancel) are fitjob.js's; this module keeps the panel's state
// and draws it. #data-panel carries
// data-state="idle|running|done|error|cancelled"; window.breakaway.fitReady() resolves
// once no fit is running. What a fit gives the explorer is fitparams.js's; the quiz of
// the mystery samples is quiz.js's.

import { ApiError, getJSON } from "../page/api.js";
import {
  cancelJob, isActive, pollJob, residualsCsv, sampleFile, submitFit,
} from "./fitjob.js";
import { paramList } from "../page/controls.js";
import { unit, unitsOfReport } from "../page/units.js";
import { drawFigure, onSchemeChange } from "../plots/draw.js";
import { addExportButtons, download, wireExports } from "../plots/export.js";
import { showFitOutputs, wireFitOutputs } from "./fitoutputs.js";
import { dataErrorMessage, explorerParams, measuredOverlay } from "./fitparams.js";
import { fitFigures, formatNumber, modelCaption } from "./fitplots.js";
import { clearPlan, drawPlanFigure, showPlan, wirePlan } from "./plan.js";
import {
  element, plotCard, renderErrorTable, renderParamTable, renderSteps, renderSummary,
} from "./fitview.js";
import {
  endQuiz, quizPending, startQuiz, wireQuiz,
} from "./quiz.js";

const panel = {
  state: "idle",
  generation: 0, // each started fit; answers for an older one are dropped
  job: null, // {id, status, ...} of the current fit
  controller: null, // aborts the current fit's requests
  source: null, // {kind: "file", file} | {kind: "sample", name}
  result: null, // the finished job {id, source, report, series}
  samples: [],
  applyParams: null,
  explorerS: () => null, // the explorer's s, for a steady report's export
  figures: null, // the shown fit's figures, redrawn when the page's style changes
};

const waiting = [];
const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------------------------
// state and status
// ---------------------------------------------------------------------------------

function setPanelState(state) {
  panel.state = state;
  const root = $("data-panel");
  root.dataset.state = state;
  $("fit-cancel").disabled = state !== "running";
  $("fit-start").disabled = !panel.source;
  if (state !== "running") {
    const resolve = waiting.splice(0);
    for (const done of resolve) done();
  }
}

function setProgress(fraction, message) {
  const bar = $("fit-progress");
  if (fraction === null) bar.removeAttribute("value"); else bar.value = fraction;
  $("fit-message").textContent = message;
}

function showError(message) {
  const box = $("fit-error");
  box.textContent = message;
  box.hidden = false;
}

function hideError() {
  $("fit-error").hidden = true;
  $("fit-error").textContent = "";
}

// ---------------------------------------------------------------------------------
// sources
// ---------------------------------------------------------------------------------

function sourceName(source) {
  if (source.kind === "file") return source.file.name || "upload.csv";
  const sample = panel.samples.find((s) => s.name === source.name);
  return `sample ${sample ? sample.title : source.name}`;
}

/** The file to upload for the current source (a sample is fetched as text). */
function sourceFile(source, signal) {
  return source.kind === "file" ? Promise.resolve(source.file) : sampleFile(source.name, signal);
}

// ---------------------------------------------------------------------------------
// a fit: submit, poll, finish
// ---------------------------------------------------------------------------------

async function startFit() {
  if (!panel.source) return;
  const previous = panel.job;
  if (panel.controller) panel.controller.abort();
  panel.generation += 1;
  const generation = panel.generation;
  const controller = new AbortController();
  panel.controller = controller;
  panel.job = null;
  if (isActive(previous)) cancelJob(previous.id); // the old fit stops at its next checkpoint
  const current = () => generation === panel.generation;

  hideError();
  clearResults();
  $("data-source").textContent = `Data: ${sourceName(panel.source)}`;
  delete $("data-panel").dataset.job;
  setPanelState("running");
  setProgress(null, "uploading");
  try {
    const file = await sourceFile(panel.source, controller.signal);
    const job = await submitFit(file, $("data-kind").value, {
      signal: controller.signal,
      isCurrent: current,
      onWaiting: () => setProgress(null, "waiting for a free fit worker"),
    });
    if (!job) return;
    if (!current()) {
      cancelJob(job.id);
      return;
    }
    panel.job = job;
    $("data-panel").dataset.job = job.id;
    await poll(generation, controller);
  } catch (error) {
    if (error.name === "AbortError" || !current()) return;
    showError(error instanceof ApiError && error.status === 422
      ? `The file could not be used: ${dataErrorMessage(error)}`
      : `The fit could not run: ${dataErrorMessage(error)}`);
    setProgress(0, "failed");
    setPanelState("error");
  }
}

async function poll(generation, controller) {
  const last = await pollJob(panel.job, {
    signal: controller.signal,
    isCurrent: () => generation === panel.generation,
    onUpdate: (job) => {
      panel.job = job;
      setProgress(job.progress, job.status === "queued" ? "waiting for a worker"
        : `${job.message} (${Math.round(job.progress * 100)} %)`);
    },
  });
  if (last) await finish(last, generation);
}

async function finish(job, generation) {
  if (job.status === "done") {
    setProgress(1, `done in ${formatNumber(job.report.seconds ?? 0, 3)} s`);
    panel.result = job;
    const sample = panel.source?.kind === "sample"
      ? panel.samples.find((s) => s.name === panel.source.name) : null;
    if (sample?.quiz) startQuiz(job.report); else endQuiz();
    await showResults(job);
    if (generation !== panel.generation) return;
    setPanelState("done");
  } else if (job.status === "cancelled") {
    setProgress(0, "cancelled");
    setPanelState("cancelled");
  } else {
    showError(`The fit failed: ${job.error ?? "unknown error"}`);
    setProgress(0, "failed");
    setPanelState("error");
  }
}

function cancelFit() {
  if (panel.state !== "running") return;
  if (panel.job && isActive(panel.job)) {
    // the job stops at its next checkpoint; polling carries on until it says "cancelled"
    setProgress(panel.job.progress, "cancelling");
    cancelJob(panel.job.id);
    return;
  }
  // still uploading: abandon the upload
  if (panel.controller) panel.controller.abort();
  panel.generation += 1;
  panel.job = null;
  setProgress(0, "cancelled");
  setPanelState("cancelled");
}

// ---------------------------------------------------------------------------------
// results
// ---------------------------------------------------------------------------------

function clearResults() {
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

async function showResults(job) {
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
function drawFitFigures() {
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
function describeFitPlot(plot) {
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

function downloadReport() {
  const job = panel.result;
  if (!job) return;
  const text = `${JSON.stringify(job.report, null, 2)}\n`;
  download(`${stem(job)}-report.json`, new Blob([text], { type: "application/json" }));
}

async function downloadResiduals() {
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

function useParameters() {
  const job = panel.result;
  if (!job || !panel.applyParams) return;
  const { values, notes, ranges, units } = explorerParams(job.report);
  const state = panel.applyParams(values, { ranges, measured: measuredOverlay(job), units });
  $("use-note").textContent = state === false
    ? "The explorer is not ready yet; try again in a moment."
    : `Set ${paramList(Object.keys(values), state)}.${notes.length ? ` Note: ${notes.join("; ")}.` : ""}`;
}

// ---------------------------------------------------------------------------------
// wiring
// ---------------------------------------------------------------------------------

function chooseFile(file) {
  if (!file) return;
  panel.source = { kind: "file", file };
  $("data-sample").value = "";
  $("sample-description").textContent = "";
  startFit();
}

function chooseSample() {
  const name = $("data-sample").value;
  const sample = panel.samples.find((s) => s.name === name);
  $("sample-description").textContent = sample ? sample.description : "";
  if (sample) {
    panel.source = { kind: "sample", name };
    $("data-source").textContent = `Data: sample ${sample.title} — press Fit`;
  }
  $("fit-start").disabled = !panel.source;
}

function wireDropZone() {
  const zone = $("drop-zone");
  const hasFiles = (event) => [...(event.dataTransfer?.types ?? [])].includes("Files");
  zone.addEventListener("dragenter", (event) => {
    if (!hasFiles(event)) return;
    event.preventDefault();
    zone.classList.add("dragging");
  });
  zone.addEventListener("dragover", (event) => {
    if (!hasFiles(event)) return;
    event.preventDefault();
    event.dataTransfer.dropEffect = "copy";
    zone.classList.add("dragging");
  });
  zone.addEventListener("dragleave", (event) => {
    if (!zone.contains(event.relatedTarget)) zone.classList.remove("dragging");
  });
  zone.addEventListener("drop", (event) => {
    event.preventDefault();
    zone.classList.remove("dragging");
    chooseFile(event.dataTransfer.files[0]);
  });
  // a file dropped beside the zone must not make the browser leave the page
  for (const type of ["dragover", "drop"]) {
    window.addEventListener(type, (event) => {
      if (hasFiles(event) && !zone.contains(event.target)) event.preventDefault();
    });
  }
}

async function loadSamples() {
  try {
    panel.samples = await getJSON("/api/samples");
  } catch {
    panel.samples = [];
  }
  const select = $("data-sample");
  for (const sample of panel.samples) {
    select.append(element("option", { value: sample.name, text: sample.title, title: sample.description }));
  }
}

/**
 * Wire the panel. `applyParams(values)` sets explorer parameters (a partial state) and
 * returns false when the explorer cannot take them yet; `tryInLoop(job, options)` opens
 * the control loop with the fitted model (fitoutputs.js); `explorerS()` is the
 * explorer's presliding scale.
 */
export function initDataPanel({ applyParams, tryInLoop, explorerS }) {
  panel.applyParams = applyParams;
  panel.explorerS = explorerS;
  wireFitOutputs({ fit: () => panel.result, showError, hideError, tryInLoop });
  wirePlan();
  $("data-file").addEventListener("change", (event) => chooseFile(event.target.files[0]));
  $("data-sample").addEventListener("change", chooseSample);
  $("fit-start").addEventListener("click", startFit);
  $("fit-cancel").addEventListener("click", cancelFit);
  $("use-params").addEventListener("click", useParameters);
  $("download-report").addEventListener("click", downloadReport);
  $("download-residuals").addEventListener("click", downloadResiduals);
  wireQuiz(() => panel.result && showResults(panel.result));
  $("present").addEventListener("change", drawFitFigures);
  onSchemeChange(drawFitFigures);
  wireDropZone();
  addExportButtons($("fit-results"));
  wireExports($("fit-results"), describeFitPlot);
  // leaving the page mid-fit frees the server's worker
  window.addEventListener("pagehide", () => {
    if (isActive(panel.job)) cancelJob(panel.job.id, true);
  });
  setPanelState("idle");
  return loadSamples();
}

/** Resolves once no fit is running (done, error, cancelled or idle). */
export function fitReady() {
  return new Promise((resolve) => {
    if (panel.state === "running") waiting.push(resolve); else resolve();
  });
}

/** The finished fit's report (a copy), or null. */
export function fitReport() {
  return panel.result ? JSON.parse(JSON.stringify(panel.result.report)) : null;
}
