// The data panel: upload measured data (file picker, drag and drop, or a bundled
// sample), fit it as a background job, and show the fit, the residuals, the diagnosis
// and the error before and after.
//
// One fit at a time from the page: starting a new one cancels the old. The job's
// requests (submit, poll, cancel) are fitjob.js's; this module keeps the panel's state
// and draws it. #data-panel carries
// data-state="idle|running|done|error|cancelled"; window.breakaway.fitReady() resolves
// once no fit is running.

import { ApiError, getJSON } from "./api.js";
import {
  cancelJob, isActive, pollJob, residualsCsv, sampleFile, submitFit,
} from "./fitjob.js";
import { PARAMS, paramSpec, roundSignificant } from "./controls.js";
import { drawFigure, onSchemeChange } from "./draw.js";
import { download } from "./export.js";
import { fitFigures, formatNumber, modelCaption } from "./fitplots.js";
import {
  element, plotCard, renderErrorTable, renderParamTable, renderSteps, renderSummary,
} from "./fitview.js";

/** Explorer parameters that "Use these parameters" sets (rounded to this many digits). */
const DIGITS = 6;
const panel = {
  state: "idle",
  generation: 0, // each started fit; answers for an older one are dropped
  job: null, // {id, status, ...} of the current fit
  controller: null, // aborts the current fit's requests
  source: null, // {kind: "file", file} | {kind: "sample", name}
  result: null, // the finished job {id, source, report, series}
  samples: [],
  applyParams: null,
  quiz: null, // {answer: [effects] | "none" | "outside"} while a puzzle is unrevealed
  figures: null, // the shown fit's figures, redrawn when the page's style changes
};

/** Effects of the library per data kind (MODEL.md §7), for the quiz's choices. */
const LIBRARY = {
  timeseries: ["viscous", "asymmetry", "offset", "drift", "inertia", "ripple", "lag", "backlash"],
  steady: ["viscous", "asymmetry", "offset"],
  breakaway: ["viscous", "asymmetry", "inertia", "dwell", "detection"],
};
const waiting = [];
const $ = (id) => document.getElementById(id);

// ---------------------------------------------------------------------------------
// pure helpers
// ---------------------------------------------------------------------------------

/**
 * The explorer values a report gives, and notes for the person: Fc, Fs, V, δ from the
 * final model (for asymmetric data these are the positive-direction levels), s when the
 * data determine it, σ when the viscous effect was found (else 0). Values are rounded to
 * DIGITS significant digits; a value beyond its slider's range is kept (the number box
 * holds any value; the slider rests at its end) and named in the notes.
 */
export function explorerParams(report, specs = PARAMS) {
  const fitted = report.final.params;
  const values = {};
  for (const name of ["Fc", "Fs", "V", "delta"]) {
    if (Number.isFinite(fitted[name])) values[name] = roundSignificant(fitted[name], DIGITS);
  }
  const notes = [];
  if (report.kind === "timeseries" && Number.isFinite(fitted.s)) {
    values.s = roundSignificant(fitted.s, DIGITS);
  } else if (report.kind === "breakaway") {
    notes.push("s is kept: a break-away fit takes it from the file (it assumes F̂ = avg, z* = 0.95)");
  } else {
    notes.push("s is kept: steady data do not determine it");
  }
  values.sigma = report.effects.includes("viscous") && Number.isFinite(fitted.sigma)
    ? roundSignificant(fitted.sigma, DIGITS) : 0;
  if (values.Fs < values.Fc) values.Fs = values.Fc; // rounding never does this; be safe
  // sliders reach the data's scale (kN for a damper): a range is widened by decades
  const ranges = {};
  const widened = [];
  for (const [name, value] of Object.entries(values)) {
    const spec = specs.find((s) => s.name === name);
    if (!spec || spec.scale === "linear" || !(value > 0)) continue;
    const min = value < spec.min ? 10 ** Math.floor(Math.log10(value / 10)) : spec.min;
    const max = value > spec.max ? 10 ** Math.ceil(Math.log10(value * 10)) : spec.max;
    if (min !== spec.min || max !== spec.max) {
      ranges[name] = { min, max };
      const low = spec.scale === "log0" ? 0 : min;
      widened.push(`${spec.symbol} ${low} … ${max}`);
    }
  }
  if (widened.length) notes.push(`slider ranges widened to the data's scale: ${widened.join(", ")}`);
  const others = Object.keys(fitted).filter((name) => !specs.some((spec) => spec.name === name));
  if (others.length) notes.push(`the explorer has no control for ${others.join(", ")}`);
  return { values, notes, ranges };
}

/** The measured points to overlay in the explorer: on the Stribeck plot (steady data),
 *  the break-away plot (break-away data) or the hysteresis loop (a time series). */
export function measuredOverlay(job) {
  const columns = job.series.columns;
  const plot = { steady: "stribeck", breakaway: "breakaway", timeseries: "hysteresis" }[job.report.kind];
  const axis = { stribeck: "v", breakaway: "k", hysteresis: "x" }[plot];
  return { plot, x: columns[axis], y: columns.measured };
}

/** The message of a bad file: the engine's sentence, with line and column if it lacks them. */
export function dataErrorMessage(error) {
  const item = error instanceof ApiError && error.detail.length ? error.detail[0] : null;
  let message = item ? item.msg : error.message;
  if (item && item.line != null && !message.includes(`line ${item.line}`)) {
    message += ` (line ${item.line}${item.column ? `, column '${item.column}'` : ""})`;
  }
  return message;
}

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
    if (sample?.quiz) startQuiz(job); else $("quiz").hidden = true;
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
  panel.quiz = null;
  $("quiz").hidden = true;
  $("fit-results").classList.remove("quiz-hidden");
  const results = $("fit-results");
  results.hidden = true;
  for (const div of results.querySelectorAll(".fit-plot")) {
    if (window.Plotly && div.data) window.Plotly.purge(div);
  }
  panel.figures = null;
  $("fit-effect-plots").replaceChildren();
  $("use-note").textContent = "";
}

// ---------------------------------------------------------------------------------
// the quiz: a mystery sample shows the data and the base model first; the diagnosis
// only after a guess
// ---------------------------------------------------------------------------------

/** The right answer of a finished report: its effects, "none" or "outside". */
export function quizAnswer(report) {
  if (report.effects.length) return report.effects;
  return report.unexplained ? "outside" : "none";
}

/** Whether `guess` (an effect name, "none" or "outside") is right for `report`. */
export function quizRight(guess, report) {
  const answer = quizAnswer(report);
  return Array.isArray(answer) ? answer.includes(guess) : guess === answer;
}

function startQuiz(job) {
  panel.quiz = { report: job.report };
  const select = $("quiz-guess");
  select.replaceChildren(element("option", { value: "", text: "(choose)" }),
    ...LIBRARY[job.report.kind].map((e) => element("option", { value: e, text: e })),
    element("option", { value: "none", text: "nothing: the base model explains it" }),
    element("option", { value: "outside", text: "something the library does not have" }));
  $("quiz-reveal").disabled = true;
  $("quiz-result").textContent = "";
  $("quiz").hidden = false;
  $("fit-results").classList.add("quiz-hidden");
}

async function revealQuiz() {
  const guess = $("quiz-guess").value;
  if (!panel.quiz || !guess || !panel.result) return;
  const report = panel.quiz.report;
  const answer = quizAnswer(report);
  const truth = Array.isArray(answer) ? `the data hold ${answer.join(" and ")}`
    : answer === "none" ? "nothing is missing: the base model explains the data"
      : "the residual keeps structure that no effect of the library explains";
  $("quiz-result").textContent = quizRight(guess, report)
    ? `Right: ${truth}.` : `Not this time: ${truth}.`;
  $("quiz-result").dataset.right = String(quizRight(guess, report));
  panel.quiz = null;
  $("fit-results").classList.remove("quiz-hidden");
  await showResults(panel.result);
}

async function showResults(job) {
  const report = job.report;
  renderSummary(job);
  renderErrorTable(report);
  renderParamTable(report);
  renderSteps(report);
  const figures = fitFigures(job);
  $("fit-model-caption").textContent = modelCaption(report.kind);
  if (panel.quiz) {
    // before the reveal: the data, the base model and its residual only
    figures.model.data = figures.model.data.filter((t) => t.name !== "final model");
    figures.residual.data = figures.residual.data.filter((t) => !t.name.startsWith("after"));
    figures.effects = [];
  }
  const effectPlots = $("fit-effect-plots");
  effectPlots.replaceChildren(...figures.effects.map(({ effect, regressor }) => plotCard(
    `fit-plot-effect-${effect}`, `${effect}: residual against ${regressor}`,
    `Where ${effect} showed: the residual against ${regressor} before (grey) and after (blue).`)));
  $("fit-results").hidden = false; // visible before drawing, so the plots take their size
  panel.figures = figures;
  await drawFitFigures();
}

/** The fit's figures as the page is shown now (again when its style changes). */
function drawFitFigures() {
  const figures = panel.figures;
  if (!figures || $("fit-results").hidden) return Promise.resolve();
  return Promise.all([
    drawFigure($("fit-plot-model"), figures.model),
    drawFigure($("fit-plot-residual"), figures.residual),
    ...figures.effects.map(({ effect, figure }) => drawFigure($(`fit-plot-effect-${effect}`), figure)),
  ]);
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
  const { values, notes, ranges } = explorerParams(job.report);
  const applied = panel.applyParams(values, { ranges, measured: measuredOverlay(job) });
  const set = Object.keys(values).map((name) => `${paramSpec(name)?.symbol ?? name} = ${values[name]}`);
  $("use-note").textContent = applied === false
    ? "The explorer is not ready yet; try again in a moment."
    : `Set ${set.join(", ")}.${notes.length ? ` Note: ${notes.join("; ")}.` : ""}`;
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
 * returns false when the explorer cannot take them yet.
 */
export function initDataPanel({ applyParams }) {
  panel.applyParams = applyParams;
  $("data-file").addEventListener("change", (event) => chooseFile(event.target.files[0]));
  $("data-sample").addEventListener("change", chooseSample);
  $("fit-start").addEventListener("click", startFit);
  $("fit-cancel").addEventListener("click", cancelFit);
  $("use-params").addEventListener("click", useParameters);
  $("download-report").addEventListener("click", downloadReport);
  $("download-residuals").addEventListener("click", downloadResiduals);
  $("quiz-guess").addEventListener("change", () => {
    $("quiz-reveal").disabled = !$("quiz-guess").value;
  });
  $("quiz-reveal").addEventListener("click", revealQuiz);
  $("present").addEventListener("change", drawFitFigures);
  onSchemeChange(drawFitFigures);
  wireDropZone();
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
