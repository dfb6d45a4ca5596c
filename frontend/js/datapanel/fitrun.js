// A fit's life from the page: its source uploaded, the job submitted and polled until it
// ends (fitjob.js's requests), its results shown or its error said; one fit at a time,
// a new one cancelling the old.

import { ApiError } from "../page/api.js";
import {
  cancelJob, isActive, pollJob, sampleFile, submitFit,
} from "./fitjob.js";
import { dataErrorMessage } from "./fitparams.js";
import { formatNumber } from "./fitplots.js";
import { clearResults, showResults } from "./fitresults.js";
import {
  $, hideError, panel, setPanelState, setProgress, showError,
} from "./panelstate.js";
import { endQuiz, startQuiz } from "./quiz.js";

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

export async function startFit() {
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

export function cancelFit() {
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
