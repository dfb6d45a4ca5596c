// The data panel's view: pure DOM builders that render a finished fit's report (the
// summary and warnings, the error and parameter tables, the diagnosis with every
// candidate's verdict and the residual structure). State and requests live elsewhere
// (datapanel.js, fitjob.js).

import { exportButtons } from "../plots/export.js";
import { formatNumber, formatWithError, paramLabel } from "./fitplots.js";

const $ = (id) => document.getElementById(id);

export function element(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs)) {
    if (key === "className") node.className = value;
    else if (key === "text") node.textContent = value;
    else node.setAttribute(key, value);
  }
  node.append(...children);
  return node;
}

export function renderSummary(job) {
  const report = job.report;
  const headline = $("fit-effects");
  headline.replaceChildren();
  if (report.effects.length) {
    headline.append(`Effect${report.effects.length > 1 ? "s" : ""} found: `);
    report.effects.forEach((effect, i) => {
      if (i) headline.append(", ");
      headline.append(element("strong", { className: "effect-name", "data-effect": effect, text: effect }));
    });
  } else if (report.unexplained) {
    headline.append("No effect of the library explains what the base model misses.");
  } else {
    headline.append("No effect missing: the base model explains the data down to the noise floor.");
  }
  const verdict = [];
  verdict.push(report.residual_white
    ? "The final residual is white: indistinguishable from measurement noise."
    : "The final residual is not white.");
  if (report.unexplained) verdict.push("Structure remains that no candidate explains.");
  const verdictBox = $("fit-verdict");
  verdictBox.textContent = verdict.join(" ");
  verdictBox.classList.toggle("unexplained", Boolean(report.unexplained));
  $("fit-warnings").replaceChildren(...(report.warnings ?? []).map((w) => element("li",
    { "data-code": w.code, ...(w.parameter ? { "data-param": w.parameter } : {}) },
    element("strong", { text: w.code }), `: ${w.message}`)));
  $("fit-meta").textContent = `${job.source}: ${report.kind}, ${report.n} rows`
    + (job.series.stride > 1 ? ` (the plots show 1 row in ${job.series.stride})` : "")
    + (report.seconds != null ? `, fitted in ${formatNumber(report.seconds, 3)} s` : "");
}

function forceUnit(report) {
  return report.units?.[report.kind === "breakaway" ? "F_ba" : "F"] ?? "N";
}

export function renderErrorTable(report) {
  const unit = forceUnit(report);
  const cell = (metric, value) => element("td", { "data-metric": metric, text: formatNumber(value, 4) });
  const body = $("fit-error-table").tBodies[0];
  body.replaceChildren(
    element("tr", {}, element("th", { scope: "row", text: `fit RMSE [${unit}]` }),
      cell("error_before", report.error_before), cell("error_after", report.error_after)),
    element("tr", {}, element("th", { scope: "row", text: `held-out RMSE [${unit}]` }),
      cell("heldout_before", report.heldout.before), cell("heldout_after", report.heldout.after)),
    element("tr", {}, element("th", { scope: "row", text: `noise floor [${unit}]` }),
      element("td", { "data-metric": "noise_floor", colspan: "2", text: formatNumber(report.noise_floor, 4) })),
  );
  // what x's resolution adds through the model: shown where there is any, beside the
  // force's own noise, so that a residual above the noise floor is read against both
  if (report.input_floor > 0) {
    body.append(element("tr", {}, element("th", { scope: "row", text: `input floor (x's resolution) [${unit}]` }),
      element("td", { "data-metric": "input_floor", colspan: "2", text: formatNumber(report.input_floor, 4) })));
  }
}

/** "moves with V (r = −0.997): Fc + 613·V = 13.28 ± 0.014 N is determined": the
 *  combination of a parameter and the one it is correlated with that the data fix. */
export function combination(name, params, tied, unit) {
  const combined = params[name] - tied.slope * params[tied.with];
  const sign = tied.slope < 0 ? "+" : "−";
  const r = `${tied.r < 0 ? "−" : ""}${Math.abs(tied.r).toFixed(3)}`;
  const shown = unit && unit !== "-" ? ` ${unit}` : "";
  return `moves with ${tied.with} (r = ${r}): ${name} ${sign} ${formatNumber(Math.abs(tied.slope), 3)}·${tied.with}`
    + ` = ${formatNumber(combined, 4)} ± ${formatNumber(tied.stderr, 2)}${shown} is determined`;
}

export function renderParamTable(report) {
  const base = report.base;
  const final = report.final;
  const names = [...new Set([...Object.keys(base.params), ...Object.keys(final.params)])];
  const body = $("fit-param-table").tBodies[0];
  body.replaceChildren(...names.map((name) => {
    // rotary data: the report's units replace the linear ones of the label
    const unit = report.units?.[name];
    const text = unit ? paramLabel(name).replace(/\[[^\]]*\]/, `[${unit}]`) : paramLabel(name);
    const label = element("th", { scope: "row", text });
    const cell = (fit, model) => {
      if (!(name in fit.params)) return element("td", { "data-model": model, text: "–" });
      const determined = fit.determined?.[name] !== false;
      const stderr = fit.stderr?.[name];
      const tied = determined ? null : report.correlated?.[model]?.[name];
      if (tied) {
        // not determined only because it moves with another: what the data do determine
        return element("td", { "data-model": model, "data-determined": "false", "data-with": tied.with,
          className: "correlated" }, formatWithError(fit.params[name], stderr),
        element("span", { className: "combination", text: combination(name, fit.params, tied, unit) }));
      }
      const text = determined ? formatWithError(fit.params[name], stderr)
        : formatNumber(fit.params[name], 4)
          + (stderr == null ? "" : ` ± ${formatNumber(stderr, 2)}`) + " ⚠ not determined";
      return element("td", { "data-model": model, "data-determined": String(determined),
        className: determined ? "" : "undetermined", text });
    };
    return element("tr", { "data-param": name }, label, cell(base, "base"), cell(final, "final"));
  }));
}

export function renderSteps(report) {
  const list = $("fit-steps");
  list.replaceChildren();
  for (const step of report.steps) {
    // the evidence sentence names the signature and the RMSE and BIC it changed
    list.append(element("li", { "data-effect": step.effect },
      element("strong", { className: "effect-name", text: step.effect }),
      `: ${step.evidence.replace(/\.?$/, ".")}`));
  }
  if (!report.steps.length) {
    list.append(element("li", { text: "No step: no candidate passed the tests (BIC, variance "
      + "explained above the noise floor, held-out error)." }));
  }
  const dropped = report.steps.map((s) => s.effect).filter((e) => !report.effects.includes(e));
  $("fit-dropped").textContent = dropped.length
    ? `Dropped again as redundant once later effects were in: ${dropped.join(", ")}.` : "";
  const candidates = report.candidates ?? {};
  const body = $("fit-candidates").tBodies[0];
  const number = (value, digits) => (value == null ? "–" : formatNumber(value, digits));
  body.replaceChildren(...Object.entries(candidates).map(([name, c]) => element("tr",
    { "data-effect": name, "data-accepted": String(Boolean(c.accepted)) },
    element("th", { scope: "row", text: name }),
    element("td", { text: number(c.rmse) }),
    element("td", { text: number(c.bic, 6) }),
    element("td", { text: number(c.heldout) }),
    element("td", { className: "verdict", text: c.accepted ? "accepted" : `not accepted: ${c.reason}` }))));
  $("fit-candidates-box").hidden = !Object.keys(candidates).length;
  const structure = report.residual_structure ?? [];
  $("fit-structure").tBodies[0].replaceChildren(...structure.map((s) => element("tr",
    { "data-against": s.against },
    element("th", { scope: "row", text: s.against }),
    element("td", { text: `${Math.round(100 * s.strength)} %` }))));
  $("fit-structure-box").hidden = !structure.length;
}

/** A card for one of the fit's figures: its title, export buttons, plot and caption
 *  (`plot`: the name its export buttons give, data-plot). */
export function plotCard(id, plot, title, caption) {
  const exports = exportButtons(plot, title);
  return element("figure", { className: "plot-card fit-card" },
    element("div", { className: "plot-head" }, element("h3", { text: title }),
      element("div", { className: "export" }, ...exports)),
    element("div", { className: "fit-plot", id, role: "group", "aria-label": title }),
    element("figcaption", { text: caption }));
}

