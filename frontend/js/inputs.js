// From the controls to the state: each slider, number box, menu and button changes
// `app.state` and hands it to the render path; committed changes become history
// entries (store.js), and Back and Forward walk through them.

import {
  KEY_STEP, PARAMS, couple, moveSlider, parseNumber, writeControls,
} from "./controls.js";
import { onSchemeChange } from "./draw.js";
import { exportCsv, exportPng } from "./export.js";
import { redraw, refresh } from "./render.js";
import { defaultState, fromQuery, presetState } from "./state.js";
import { $, app, commit } from "./store.js";
import { drawView } from "./viewrequests.js";
import { requestViews } from "./views.js";

/** Show `state`: into the controls, the history (unless `push` is false), the plots. */
export function setState(state, { push = true } = {}) {
  app.state = state;
  writeControls(state);
  if (push) commit();
  refresh();
}

/** Every plot drawn again as the page is styled now (presentation mode, dark mode). */
function restyle() {
  if (!app.frame) return;
  redraw();
  for (const view of requestViews()) drawView(view.id);
}

function wireParameters() {
  for (const spec of PARAMS) {
    const box = $(spec.name);
    const range = $(`${spec.name}-range`);
    range.addEventListener("input", () => {
      const coupled = moveSlider(app.state, spec, range.value);
      box.value = String(app.state[spec.name]);
      if (coupled) writeControls(app.state, { except: range });
      refresh();
    });
    range.addEventListener("keydown", (event) => {
      const step = KEY_STEP[event.key];
      app.lastStep = step ? { spec, step } : null;
    });
    range.addEventListener("pointerdown", () => { app.lastStep = null; });
    box.addEventListener("input", () => {
      const value = parseNumber(box.value);
      app.state[spec.name] = Number.isNaN(value) ? box.value : value;
      couple(app.state, spec.name);
      writeControls(app.state, { except: box });
      refresh();
    });
    range.addEventListener("change", commit);
    box.addEventListener("change", commit);
  }
}

export function wireControls() {
  wireParameters();
  $("F_hat").addEventListener("change", () => {
    app.state.F_hat = $("F_hat").value;
    commit();
    refresh();
  });
  $("present").addEventListener("change", () => {
    app.state.present = $("present").checked;
    document.body.classList.toggle("present", app.state.present);
    commit();
    restyle();
  });
  onSchemeChange(restyle);
  $("preset").addEventListener("change", () => {
    const preset = app.presets.find((p) => p.name === $("preset").value);
    if (preset) setState(presetState(preset, app.defaults, app.state));
  });
  $("reset").addEventListener("click", () => setState(defaultState(app.defaults)));
  $("copy-link").addEventListener("click", async () => {
    // said under the button, where the person looks; where the clipboard is refused
    // (no permission, no secure context) the link is shown to copy by hand
    const status = $("copy-status");
    try {
      await navigator.clipboard.writeText(window.location.href);
      status.textContent = "Link copied.";
    } catch {
      status.textContent = `Copy this link: ${window.location.href}`;
    }
  });
  for (const button of document.querySelectorAll("[data-export]")) {
    button.addEventListener("click", () => {
      if (button.dataset.export === "csv") exportCsv(button.dataset.plot);
      else exportPng(button.dataset.plot);
    });
  }
  window.addEventListener("popstate", () => {
    app.commitPending = false; // the entry walked to is the state now
    setState(fromQuery(window.location.search, app.defaults), { push: false });
  });
}
