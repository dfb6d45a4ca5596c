// The one integrator of the page's dynamic models (rampmodel.js, loopmodel.js): the
// server's (backend/breakaway/dynamics/integrator.py) step by step, an adaptive
// Dormand–Prince 5(4) scheme with event location on each step's Hermite interpolant and
// an exact restart at every jump. A model is an object of functions of (t, y) over its
// own parameters and memory, as in dynamics/table.py:
//   n                    the number of states
//   rhs(t, y, dy)        the right-hand side
//   force(t, y)          the friction [N]
//   guard(t, y)          passes from >= 0 to < 0 at an event
//   jump(t, y)           updates the memory at an event; returns the event code
//   stop(t, y)           the run ends where it passes 0 upwards
//   stopRises            whether stop only rises between jumps (one look per step)
// A run records through `record(t, y, code)`: every accepted step and event, or
// (nGrid >= 2) the uniform grid over [0, tEnd], interpolated, plus the events whose code
// shares a bit with eventMask.

import { shape } from "./model.js";

export const STATUS_STOP = 0;
export const STATUS_END = 1;
export const STATUS_STEP_LIMIT = 2;
/** runs.DEFAULT_RTOL and runs._H_MAX_FRACTION. */
export const RTOL = 1e-6;
export const H_MAX_FRACTION = 1e-3;
/** dynamics.common's event codes. */
export const EVENT_REVERSAL = 1;
export const EVENT_BREAKAWAY = 2;
export const EVENT_STICK = 4;
export const EVENT_COMPENSATION = 8;
/** integrator._SCAN_POINTS: the guard's look inside each step for a short excursion. */
const SCAN_POINTS = 4;

// Dormand–Prince 5(4) tableau
const C2 = 1 / 5; const C3 = 3 / 10; const C4 = 4 / 5; const C5 = 8 / 9;
const A21 = 1 / 5;
const A31 = 3 / 40; const A32 = 9 / 40;
const A41 = 44 / 45; const A42 = -56 / 15; const A43 = 32 / 9;
const A51 = 19372 / 6561; const A52 = -25360 / 2187; const A53 = 64448 / 6561; const A54 = -212 / 729;
const A61 = 9017 / 3168; const A62 = -355 / 33; const A63 = 46732 / 5247; const A64 = 49 / 176;
const A65 = -5103 / 18656;
const B1 = 35 / 384; const B3 = 500 / 1113; const B4 = 125 / 192; const B5 = -2187 / 6784;
const B6 = 11 / 84;
const E1 = 71 / 57600; const E3 = -71 / 16695; const E4 = 71 / 1920; const E5 = -17253 / 339200;
const E6 = 22 / 525; const E7 = -1 / 40;

function hermite(y0, f0, y1, f1, h, theta, out) {
  const t2 = theta * theta;
  const t3 = t2 * theta;
  const h00 = 2 * t3 - 3 * t2 + 1;
  const h10 = t3 - 2 * t2 + theta;
  const h01 = -2 * t3 + 3 * t2;
  const h11 = t3 - t2;
  for (let i = 0; i < y0.length; i += 1) {
    out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i];
  }
}

/** norm^(-1/5), the step's change for an error `norm` of the 4th-order estimate, as
 *  exp and log (integrator._step_factor): V8's pow takes three times as long, a
 *  twentieth of a run. */
function stepFactor(norm) {
  return Math.exp(-0.2 * Math.log(norm));
}

const EVENT_STOP = 0;
const EVENT_GUARD = 1;

function event(model, which, t, y) {
  return which === EVENT_STOP ? -model.stop(t, y) : model.guard(t, y);
}

/** integrator._first_crossing: the first θ in (0, thetaMax] where event `which` passes
 *  from >= 0 to < 0 along the interpolant, the state there left in `work`; -1 if none. */
function firstCrossing(model, which, t0, y0, f0, y1, f1, h, work, thetaMax, scan) {
  let lo = 0.0;
  if (event(model, which, t0, y0) < 0) return -1.0;
  const points = scan ? SCAN_POINTS : 1;
  let hi = 0.0;
  let found = false;
  for (let j = 1; j <= points; j += 1) {
    hi = (thetaMax * j) / points;
    if (hi === 1.0) work.set(y1);
    else hermite(y0, f0, y1, f1, h, hi, work);
    if (event(model, which, t0 + hi * h, work) < 0) {
      found = true;
      break;
    }
    lo = hi;
  }
  if (!found) return -1.0;
  for (let i = 0; i < 60; i += 1) {
    const mid = 0.5 * (lo + hi);
    hermite(y0, f0, y1, f1, h, mid, work);
    if (event(model, which, t0 + mid * h, work) >= 0) lo = mid;
    else hi = mid;
    if (hi - lo < 1e-15) break;
  }
  hermite(y0, f0, y1, f1, h, hi, work);
  return hi;
}

/**
 * Integrate `model` from t = 0 and state `y` (changed in place) until its stop fires,
 * tEnd or maxSteps (integrator._integrate). Returns {status, t, F, jumps}.
 */
export function integrate(model, y, {
  tEnd, atol, maxSteps, record, rtol = RTOL, nGrid = 0, eventMask = -1, eventRoom = 20_000,
}) {
  const n = model.n;
  const hMax = tEnd * H_MAX_FRACTION;
  const [k1, k2, k3, k4, k5, k6, k7, ytmp, ynew, work, gridWork] = Array.from({ length: 11 },
    () => new Float64Array(n));
  const everyStep = nGrid === 0;
  let t = 0.0;
  let h = Math.min(hMax, tEnd * 1e-6);
  let jumps = 0;
  let room = eventRoom;
  let jGrid = 1; // the next grid sample (t = 0 is recorded)
  model.rhs(t, y, k1);
  record(t, y, 0);
  for (let step = 0; step < maxSteps; step += 1) {
    if (t >= tEnd) return { status: STATUS_END, t, F: model.force(t, y), jumps };
    h = Math.min(h, hMax, tEnd - t);
    for (let i = 0; i < n; i += 1) ytmp[i] = y[i] + h * A21 * k1[i];
    model.rhs(t + C2 * h, ytmp, k2);
    for (let i = 0; i < n; i += 1) ytmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
    model.rhs(t + C3 * h, ytmp, k3);
    for (let i = 0; i < n; i += 1) ytmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
    model.rhs(t + C4 * h, ytmp, k4);
    for (let i = 0; i < n; i += 1) {
      ytmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
    }
    model.rhs(t + C5 * h, ytmp, k5);
    for (let i = 0; i < n; i += 1) {
      ytmp[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
    }
    model.rhs(t + h, ytmp, k6);
    for (let i = 0; i < n; i += 1) {
      ynew[i] = y[i] + h * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i] + B6 * k6[i]);
    }
    model.rhs(t + h, ynew, k7);
    let norm = 0.0;
    for (let i = 0; i < n; i += 1) {
      const e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
      const scale = atol[i] + rtol * Math.max(Math.abs(y[i]), Math.abs(ynew[i]));
      norm += (e / scale) ** 2;
    }
    norm = Math.sqrt(norm / n);
    if (!(norm <= 1.0)) {
      h *= norm === norm ? Math.max(0.2, 0.9 * stepFactor(norm)) : 0.2;
      continue;
    }
    // accepted step [t, t + h]: the earlier of the stop and a jump wins
    const thetaJump = firstCrossing(model, EVENT_GUARD, t, y, k1, ynew, k7, h, ytmp, 1.0, true);
    const thetaEnd = thetaJump >= 0 ? thetaJump : 1.0;
    const thetaStop = firstCrossing(model, EVENT_STOP, t, y, k1, ynew, k7, h, work, thetaEnd,
      !model.stopRises);
    const thetaDone = thetaStop >= 0 ? thetaStop : thetaEnd;
    if (!everyStep) {
      // the grid's samples in (t, t + θ·h], interpolated (integrator._record_grid)
      const t1 = t + thetaDone * h;
      while (jGrid < nGrid) {
        const tGrid = (tEnd * jGrid) / (nGrid - 1);
        if (tGrid > t1) break;
        hermite(y, k1, ynew, k7, h, (tGrid - t) / h, gridWork);
        record(tGrid, gridWork, 0);
        jGrid += 1;
      }
    }
    if (thetaStop >= 0) {
      const tStop = t + thetaStop * h;
      y.set(work);
      const F = model.force(tStop, y);
      record(tStop, y, 0);
      return { status: STATUS_STOP, t: tStop, F, jumps };
    }
    if (thetaJump >= 0) {
      t += thetaJump * h;
      y.set(ytmp);
      const code = model.jump(t, y);
      jumps += 1;
      if (everyStep) record(t, y, code);
      else if ((code & eventMask) && room > 0) {
        record(t, y, code);
        room -= 1;
      }
      model.rhs(t, y, k1);
      // a new presliding branch starts with an infinite stiffness: restart at a tenth
      if (code & EVENT_REVERSAL) h = Math.max(h * 0.1, 1e-14 * Math.max(t, 1.0));
      continue;
    }
    t += h;
    y.set(ynew);
    k1.set(k7);
    if (everyStep) record(t, y, 0);
    h *= Math.min(5.0, 0.9 * stepFactor(Math.max(norm, 1e-10)));
  }
  return { status: STATUS_STEP_LIMIT, t, F: model.force(t, y), jumps };
}

/** g(v) of (E2) with its limits at v = 0 (dynamics.common._g). */
export function g(v, Fc, Fs, V, delta) {
  const av = Math.abs(v);
  if (av === 0.0) return delta > 0 ? Fs : Fc;
  return Fc + (Fs - Fc) * Math.exp(-((av / V) ** delta));
}

/** g on a branch of motion for u = d·v, its speed along the branch's direction d
 *  (dynamics.common._g_branch): g(|v|) while u >= 0, continued past the reversal that
 *  ends the branch (seen only inside a step the reversal cuts) as an odd (u/V)^δ, so
 *  that the step across it is not refused for g's kink. */
export function gBranch(u, Fc, Fs, V, delta) {
  if (u >= 0.0 || delta < 0) return g(u, Fc, Fs, V, delta);
  return Fc + (Fs - Fc) * Math.exp((-u / V) ** delta);
}

/** The presliding friction of (E6') for y = [x, v, …] and mem = [x_r, F_r, d, …]
 *  (ramp_model._presliding_force); `p`: Fc, Fs, V, delta, sigma, s. */
export function preslidingForce(y, p, mem) {
  const z = p.s * Math.abs(y[0] - mem[0]);
  const target = mem[2] * gBranch(mem[2] * y[1], p.Fc, p.Fs, p.V, p.delta) + p.sigma * y[1];
  return mem[1] + (target - mem[1]) * shape(z);
}

/** The checks of params.check_stribeck. */
export function validStribeck(p) {
  return [p.Fc, p.Fs, p.V, p.delta, p.sigma].every(Number.isFinite) && p.Fc > 0
    && p.Fs >= p.Fc && p.V > 0 && p.delta !== 0 && p.sigma >= 0;
}
