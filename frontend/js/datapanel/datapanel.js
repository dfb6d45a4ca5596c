// The data panel: upload measured data (file picker, drag and drop, or a bundled
// sample), fit it as a background job, and show the fit, the residuals, the diagnosis
// and the error before and after.
//
// One fit at a time from the page: starting a new one cancels the old (fitrun.js, with
// fitjob.js's requests); the panel's state is panelstate.js's, a finished fit's view
// fitresults.js's; this module chooses the data and wires the panel. #data-panel carries
// data-state="idle|running|done|error|cancelled"; window.breakaway.fitReady() resolves
// once no fit is running. What a fit gives the explorer is fitparams.js's; the quiz of
// the mystery samples is quiz.js's.

import { getJSON } from "../page/api.js";
import { onSchemeChange } from "../plots/draw.js";
import { addExportButtons, wireExports } from "../plots/export.js";
import { cancelJob, isActive } from "./fitjob.js";
import { wireFitOutputs } from "./fitoutputs.js";
import {
  describeFitPlot, downloadReport, downloadResiduals, drawFitFigures, showResults, useParameters,
} from "./fitresults.js";
import { cancelFit, startFit } from "./fitrun.js";
import { element } from "./fitview.js";
import {
  $, hideError, panel, setPanelState, showError,
} from "./panelstate.js";
import { wirePlan } from "./plan.js";
import { wireQuiz } from "./quiz.js";

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
