// The sentence under the control loop, as pure functions, each clause built from the
// run's facts and in the state's units: whether the loop hunts (its period and
// amplitude) or settles, and why: Fs > Fc with integral action, what ramps u while the
// body sticks (each stick a ramp experiment that E13 predicts), Kd against the Stribeck
// curve's steepest fall, a force limit. What Fs = Fc, more Kd and compensation would
// change is said from runs of those variants (whatIfStates), never assumed:
// compensation from ṙ can make a loop worse, and the sentence says so when the numbers do.

import { fmt, quantity } from "../page/units.js";
import { compParams, compScale, niceUp } from "./loopstate.js";
import { paramList } from "../page/controls.js";

/**
 * The Stribeck curve's steepest fall, max over v > 0 of −d/dv [Fc + (Fs − Fc)·
 * exp(−(v/V)^δ)] [N·s/m] (E2 without σ): the negative damping sliding meets. 0 when the
 * curve does not fall (Fs = Fc, δ < 0); Infinity for 0 < δ < 1 (vertical at v = 0).
 * With δ = 1 it is (Fs − Fc)/V; with δ > 1 at (v/V)^δ = (δ − 1)/δ.
 */
export function steepestFall({ Fc, Fs, V, delta }) {
  const drop = Number(Fs) - Number(Fc);
  const d = Number(delta);
  if (!(drop > 0) || d < 0) return 0;
  if (d < 1) return Infinity;
  const u = ((d - 1) / d) ** (1 / d);
  return (drop / Number(V)) * d * u ** (d - 1) * Math.exp(-(u ** d));
}

/** What a run shows: its verdict and the numbers the sentence quotes. */
export function summarise(loop) {
  const end = loop.duration;
  let band = 0;
  for (let i = 0; i < loop.t.length; i += 1) {
    if (loop.t[i] >= end / 2) band = Math.max(band, Math.abs(loop.e[i]));
  }
  const late = loop.stick_phases.filter((phase) => phase.t_ba >= end / 2).length;
  const ref = loop.reference;
  const size = ref.kind === "ramp" ? ref.w * end : ref.h;
  const eEnd = loop.e[loop.e.length - 1];
  let verdict = "moving";
  if (loop.runaway) verdict = "runaway";
  else if (loop.hunting) verdict = "hunts";
  else if (!late && Math.abs(eEnd) <= 0.01 * size) verdict = "settles";
  else if (!late) verdict = "stuck";
  // below a millionth of the reference's size, e is the integration's rounding
  const end0 = Math.abs(eEnd) < 1e-6 * size ? 0 : eEnd;
  return { verdict, band, late, eEnd: end0, rms: loop.rms_error, hunting: loop.hunting };
}

/** The gain Kd the sentence tries for "more Kd": enough to outweigh the steepest fall
 *  (Kd + σ ≥ it), at least twice the current; null when there is nothing to try. */
export function moreKd(state) {
  const need = steepestFall(state) - Number(state.sigma);
  const Kd = Number(state.Kd);
  if (Number.isFinite(need) && need > 0) return niceUp(Math.max(2 * Kd, need));
  return Kd > 0 ? niceUp(2 * Kd) : null;
}

/** The variants whose runs say what would change: Fs = Fc, more Kd, the compensation
 *  switched (off ↔ exact), and switched at the larger Kd (a sine or a ramp). Asked for
 *  when the loop hunts or compensates, and does not run away. */
export function whatIfStates(state, loop) {
  if (loop.runaway || !(loop.hunting || compScale(state) > 0)) return {};
  const out = {};
  const toggled = (s) => ({ ...s, comp: compScale(s) > 0 ? "off" : "exact" });
  if (Number(state.Fs) > Number(state.Fc)) out.fsfc = { ...state, Fs: state.Fc };
  const Kd = moreKd(state);
  if (Kd != null) out.kd = { ...state, Kd };
  out.comp = toggled(state);
  if (Kd != null && state.ref !== "step") out.compKd = toggled(out.kd);
  return out;
}

/** Whether the Stribeck curve falls as the body starts to slide (velocity weakening). */
function weakening(state) {
  return Number(state.Fs) > Number(state.Fc) && Number(state.delta) > 0;
}

/** What ramps u while the body sticks: the integral term, and the proportional term
 *  while the reference moves away (a ramp or a sine). */
function rampingTerms(state) {
  const terms = [];
  if (Number(state.Ki) > 0) terms.push("the integral term (k ≈ Ki·|e|)");
  if (state.ref !== "step" && Number(state.Kp) > 0) terms.push("the proportional term as the reference moves on (Kp·ṙ)");
  return terms;
}

function verdictSentence(loop, state, s) {
  const q = (value, linear) => quantity(value, linear, state);
  const end = loop.duration;
  if (s.verdict === "runaway") {
    const KdKp = Number(state.Kd) * Number(state.Kp);
    const mKi = Number(state.m_loop) * Number(state.Ki);
    return `The loop is unstable: |e| grew past 100 times the reference's size by t = ${q(loop.t_end, "s")}.`
      + (KdKp <= mKi ? ` Its linear part needs Kd·Kp > m·Ki, and here Kd·Kp = ${fmt(KdKp)} ≤ m·Ki = `
        + `${q(mKi, "N²·s/m²")}: lower Ki or the loop mass, or raise Kd.` : "");
  }
  const cut = loop.t_end < end ? ` The run ended at t = ${q(loop.t_end, "s")} (the simulation's step budget).` : "";
  const rms = `RMS error ${q(s.rms, "m")}`;
  if (s.verdict === "hunts") {
    const h = s.hunting;
    const what = loop.reference.kind === "step" ? "The loop hunts" : `The loop hunts (stick-slip along the ${loop.reference.kind})`;
    const cycle = Number.isFinite(h.cycle) && Math.abs(h.cycle - h.period) > 0.01 * h.period
      ? ` (a full cycle ${q(h.cycle, "s")})` : "";
    const band = Number.isFinite(h.amplitude) ? `, e within ±${q(h.amplitude, "m")} in the last half` : "";
    return `${what}: ${h.count} break-aways in the last ${q(end / 2, "s")}, one every ${q(h.period, "s")}`
      + `${cycle}${band}; ${rms}.${cut}`;
  }
  if (s.verdict === "settles") {
    return `The loop settles: no break-away in the last half, e = ${q(s.eEnd, "m")} at the end `
      + `(|e| ≤ ${q(s.band, "m")} over the last half); ${rms}.${cut}`;
  }
  if (s.verdict === "stuck") {
    return loop.reference.kind === "step"
      ? `The loop does not hunt, but stops short: the body sticks with e = ${q(s.eEnd, "m")} left; ${rms}.${cut}`
      : `The loop does not hunt: ${loop.stick_phases.length} break-aways, none in the last half; ${rms}.${cut}`;
  }
  return `The loop does not settle within ${q(end, "s")}: ${s.late} break-away${s.late === 1 ? "" : "s"} in the `
    + `last half, too few to call it hunting; e = ${q(s.eEnd, "m")} at the end, ${rms}.${cut}`;
}

function kdClause(state) {
  const fall = steepestFall(state);
  const damping = Number(state.Kd) + Number(state.sigma);
  if (fall === 0) return "";
  const steepest = Number.isFinite(fall) ? quantity(fall, "N·s/m", state) : "unbounded at v = 0 (δ < 1)";
  return damping < fall
    ? `Kd + σ = ${quantity(damping, "N·s/m", state)} is below the Stribeck curve's steepest fall, ${steepest}, so sliding is not damped.`
    : `Kd + σ = ${quantity(damping, "N·s/m", state)} outweighs the Stribeck curve's steepest fall, ${steepest}, so sliding is damped.`;
}

/** The force limit, when it keeps u below what breaks the body away: null otherwise. */
function heldByLimit(state) {
  return state.limit && Number(state.u_max) < Number(state.Fs) ? Number(state.u_max) : null;
}

function whySentence(loop, state, s) {
  const q = (value, linear) => quantity(value, linear, state);
  const Fc = Number(state.Fc);
  const Fs = Number(state.Fs);
  const Ki = Number(state.Ki);
  // the last stick that ramped u towards its break-away (k > 0: E13 has a value)
  const last = loop.stick_phases.filter((phase) => phase.k > 0).pop();
  const parts = [];
  if (s.verdict === "hunts") {
    const stiction = Fs > Fc && Ki > 0
      ? `Why: Fs = ${q(Fs, "N")} > Fc = ${q(Fc, "N")} with integral action (Ki = ${q(Ki, "N/(m·s)")}). `
      : "Why: ";
    const terms = rampingTerms(state);
    const numbers = last && Number.isFinite(last.E13) ? `: the last stick broke away at |u| = ${q(Math.abs(last.u_ba), "N")} `
      + `with k = ${q(last.k, "N/s")}, where E13 (F̂ = ${state.F_hat}) says ${q(Math.abs(last.E13), "N")}` : "";
    const ramp = terms.length
      ? `While the body sticks, ${terms.join(" and ")} ramp${terms.length === 1 ? "s" : ""} u until it reaches the `
        + `break-away force, the note's ramp experiment${numbers}.`
      : `The body sticks and breaks away again and again${numbers}.`;
    const slide = weakening(state)
      ? " Sliding, friction falls towards Fc, so the body overshoots"
        + (Ki > 0 ? ", and the wound-up integral sticks it on the other side." : ".")
      : "";
    parts.push(`${stiction}${ramp}${slide}`);
    parts.push(kdClause(state));
  } else if (s.verdict === "settles" && Fs <= Fc) {
    parts.push("It settles because Fs = Fc: friction does not fall once the body slides, so nothing overshoots.");
  } else if (s.verdict === "settles" && Ki > 0) {
    const damped = Number(state.Kd) + Number(state.sigma) >= steepestFall(state);
    parts.push(`It settles although Fs > Fc.${damped && kdClause(state) ? ` ${kdClause(state)}` : ""}`);
  } else if (s.verdict === "stuck" && loop.reference.kind === "step") {
    const limit = heldByLimit(state);
    const push = Number(state.Kp) * Math.abs(s.eEnd);
    if (limit != null) {
      parts.push(`The force limit ±${q(limit, "N")} lies below the break-away force (Fs = ${q(Fs, "N")}): `
        + "u cannot break the body away.");
    } else if (Ki > 0) {
      parts.push(`The integral term ramps u at only k ≈ Ki·|e| = ${q(Ki * Math.abs(s.eEnd), "N/s")}: `
        + "the next break-away comes after the run.");
    } else if (push < Fs) {
      parts.push(`Without integral action (Ki = 0) nothing ramps u while the body sticks: Kp·|e| = `
        + `${q(push, "N")} stays short of the break-away force (Fs = ${q(Fs, "N")}).`);
    }
  }
  if (state.limit) {
    const limit = Number(state.u_max);
    const held = loop.u.filter((u) => Math.abs(u) >= 0.999 * limit).length / loop.u.length;
    if (held > 0) {
      parts.push(`u sat on its limit ±${q(limit, "N")} for ${fmt(100 * held, 2)} % of the run`
        + (Ki > 0 ? " while the integral kept growing (integral windup), which prolongs each overshoot." : "."));
    }
  }
  const own = compParams(state);
  if (compScale(state) > 0 && state.comp_model === "fitted" && own) {
    const names = ["Fc", "Fs", "V"];
    parts.push(`The compensator uses the fitted model (${paramList(names, state, { values: own })}) while the `
      + `plant has the sliders' (${paramList(names, state)}).`);
  }
  return parts.filter(Boolean).join(" ");
}

function outcome(s, state) {
  const q = (value, linear) => quantity(value, linear, state);
  if (s.verdict === "runaway") return "runs away";
  if (s.verdict === "hunts") {
    const band = Number.isFinite(s.hunting.amplitude) ? `, ±${q(s.hunting.amplitude, "m")}` : "";
    return `still hunts (a break-away every ${q(s.hunting.period, "s")}${band})`;
  }
  if (s.verdict === "settles") return `settles (e = ${q(s.eEnd, "m")} at the end)`;
  return `does not hunt (RMS error ${q(s.rms, "m")})`;
}

/** Whether a run's body sticks and slips (hunts, or breaks away in its last half). */
function sticksAndSlips(s) {
  return s.verdict === "hunts" || s.late > 0;
}

function compensationSentence(state, s, whatifs, kdStates) {
  const q = (value, linear) => quantity(value, linear, state);
  const on = compScale(state) > 0;
  const [withC, without] = on ? [s, whatifs.comp] : [whatifs.comp, s];
  const change = (withC.rms - without.rms) / without.rms;
  const c = on ? compScale(state) : 1;
  const subject = on ? `Compensation (c = ${fmt(c)})` : "Exact compensation (c = 1)";
  const verb = (word) => (on ? `${word}s` : `would ${word}`);
  if (!Number.isFinite(change) || Math.abs(change) < 0.005) {
    return state.ref === "step"
      ? `${subject} changes nothing here: it adds c·Fss(ṙ), and a step's ṙ is 0 after t = 0.`
      : `${subject} changes the RMS error by less than 0.5 %.`;
  }
  const from = `the RMS error from ${q(without.rms, "m")} to ${q(withC.rms, "m")}`;
  if (change < 0) return `${subject} ${verb("lower")} ${from}.`;
  let sentence = `${subject} ${verb("raise")} ${from}`;
  sentence += sticksAndSlips(withC)
    ? `: Fss(ṙ) assumes the body follows the reference's velocity ṙ, but at Kd = ${q(Number(state.Kd), "N·s/m")} `
      + "it sticks and slips instead, so the added force comes at the wrong moments."
    : ".";
  if (kdStates) {
    const [kdWith, kdWithout] = on ? [kdStates.kd, kdStates.compKd] : [kdStates.compKd, kdStates.kd];
    sentence += kdWith.rms < kdWithout.rms
      ? ` At Kd = ${q(kdStates.Kd, "N·s/m")} it lowers it instead, from ${q(kdWithout.rms, "m")} to ${q(kdWith.rms, "m")}.`
      : ` At Kd = ${q(kdStates.Kd, "N·s/m")} it does not help either (${q(kdWith.rms, "m")} against ${q(kdWithout.rms, "m")}).`;
  }
  return sentence;
}

function whatIfSentence(state, s, whatifs) {
  const parts = [];
  const changes = [];
  if (whatifs.fsfc) changes.push(`with Fs = Fc the same loop ${outcome(whatifs.fsfc, state)}`);
  if (whatifs.kd && s.verdict === "hunts") {
    const fall = steepestFall(state);
    const enough = Number(whatifs.kdValue) + Number(state.sigma) >= fall;
    changes.push(`with Kd = ${quantity(whatifs.kdValue, "N·s/m", state)}${enough ? " (Kd + σ past the steepest fall)" : ""} `
      + `it ${outcome(whatifs.kd, state)}`);
  }
  if (changes.length) {
    const text = changes.join("; ");
    parts.push(`${text[0].toUpperCase()}${text.slice(1)}.`);
  }
  if (whatifs.comp) {
    const kdStates = whatifs.kd && whatifs.compKd ? { kd: whatifs.kd, compKd: whatifs.compKd, Kd: whatifs.kdValue } : null;
    parts.push(compensationSentence(state, s, whatifs, kdStates));
  }
  return parts.join(" ");
}

/**
 * The sentence for run `loop` of `state`. `whatifs`: the summaries of whatIfStates'
 * runs ({fsfc?, kd?, kdValue?, comp?, compKd?}), null while they are on their way
 * (`pending`) or not asked for.
 */
export function explainLoop(loop, state, whatifs = null, pending = false) {
  const s = summarise(loop);
  const parts = [verdictSentence(loop, state, s)];
  if (s.verdict !== "runaway") parts.push(whySentence(loop, state, s));
  if (whatifs) parts.push(whatIfSentence(state, s, whatifs));
  else if (pending) parts.push("(Checking what Fs = Fc, more Kd and compensation would change…)");
  return parts.filter(Boolean).join(" ");
}
