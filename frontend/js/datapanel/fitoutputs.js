// What a finished fit gives away: the fitted model as code (POST /api/export: its JSON,
// a Python module, a C99 file) and the model tried in the explorer's control loop. A
// steady report has no presliding scale: the export takes the one in the panel's box
// (the explorer's s to start with). A failed export says what the server named.

import { ApiError } from "../page/api.js";
import { parseNumber } from "../page/controls.js";
import { download } from "../plots/export.js";

const LANGS = { json: "JSON", python: "Python", c: "C99" };
const $ = (id) => document.getElementById(id);

/** The text of the fitted model in `lang`, and the file name the server gives it. */
export async function exportModel(report, lang, s = null) {
  const body = { report, lang, ...(s == null ? {} : { s }) };
  const response = await fetch("/api/export", {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  if (!response.ok) {
    let detail = [];
    try {
      detail = (await response.json()).detail;
    } catch {
      // not JSON: the status says it
    }
    throw new ApiError(response.status, typeof detail === "string" ? [{ msg: detail }] : detail);
  }
  const named = /filename="([^"]+)"/.exec(response.headers.get("Content-Disposition") ?? "");
  return {
    text: await response.text(),
    filename: named ? named[1] : `friction_model.${lang === "python" ? "py" : lang}`,
    type: response.headers.get("Content-Type") ?? "text/plain",
  };
}

/** The sentence for a failed export: the server's message and the report key it names. */
export function exportErrorMessage(error, lang) {
  const item = error instanceof ApiError ? error.detail[0] : null;
  const where = (item?.loc ?? []).filter((part) => part !== "body").join(".");
  const status = error instanceof ApiError ? ` (HTTP ${error.status}${where ? `, at ${where}` : ""})` : "";
  return `The model could not be exported as ${LANGS[lang]}: ${error.message}${status}.`;
}

/**
 * Wire the panel's model outputs. `fit()` is the finished fit (or null); `showError`
 * and `hideError` the panel's alert; `tryInLoop(job, {compensatorOnly})` opens the
 * explorer's loop with the fitted model and returns a sentence for the panel (or false
 * when the explorer is not ready).
 */
export function wireFitOutputs({ fit, showError, hideError, tryInLoop }) {
  for (const lang of Object.keys(LANGS)) {
    $(`download-model-${lang}`).addEventListener("click", async () => {
      const job = fit();
      if (!job) return;
      hideError();
      const box = $("export-s-row").hidden ? null : parseNumber($("export-s").value);
      if (box != null && !(box > 0)) {
        showError("The model could not be exported: the presliding scale s must be a number > 0.");
        return;
      }
      try {
        const file = await exportModel(job.report, lang, box);
        download(file.filename, new Blob([file.text], { type: file.type }));
      } catch (error) {
        showError(exportErrorMessage(error, lang));
      }
    });
  }
  $("try-loop").addEventListener("click", () => {
    const job = fit();
    if (!job) return;
    const said = tryInLoop(job, { compensatorOnly: $("try-loop-compensator").checked });
    $("use-note").textContent = said === false ? "The explorer is not ready yet; try again in a moment." : said;
  });
}

/** A new report shown: the box for s when its kind leaves s open (steady data). */
export function showFitOutputs(report, explorerS) {
  const open = report.kind === "steady";
  $("export-s-row").hidden = !open;
  $("export-s-help").hidden = !open;
  if (open) $("export-s").value = String(explorerS ?? 1);
}
