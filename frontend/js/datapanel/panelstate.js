// The data panel's state, shared by its modules: the current fit and its source, the
// panel's status (#data-panel's data-state="idle|running|done|error|cancelled"), its
// progress bar and error box, and who waits for the running fit to end.

export const panel = {
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
export const $ = (id) => document.getElementById(id);

export function setPanelState(state) {
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

export function setProgress(fraction, message) {
  const bar = $("fit-progress");
  if (fraction === null) bar.removeAttribute("value"); else bar.value = fraction;
  $("fit-message").textContent = message;
}

export function showError(message) {
  const box = $("fit-error");
  box.textContent = message;
  box.hidden = false;
}

export function hideError() {
  $("fit-error").hidden = true;
  $("fit-error").textContent = "";
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
