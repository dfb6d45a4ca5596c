// The ramp experiment computed in the page, for the frames drawn while a hand moves the
// mass m (the one slider that moves only the ramp): the answer of POST /api/ramp for the
// presliding model (backend/breakaway/ramp.py), from the same integrator step by step
// (backend/breakaway/dynamics/integrator.py: Dormand–Prince 5(4), event location on
// each step's Hermite interpolant, a restart at every reversal) and the same model
// (ramp_model.py: E7 with E6'). tests/browser/test_browser_rampmodel_js.py holds it to
// the Python run. A run that needs more than LIVE_MAX_STEPS steps (a chattering stick at
// a small rate) is left to the server: null.

import { breakawayForce } from "./model.js";

/** Steps the page integrates at most for one live frame (a few ms); beyond, the server. */
export const LIVE_MAX_STEPS = 20_000;
/** Samples of the answer at most (ramp.MAX_POINTS). */
const MAX_POINTS = 2000;
/** runs.DEFAULT_RTOL and runs._H_MAX_FRACTION. */
const RTOL = 1e-6;
const H_MAX_FRACTION = 1e-3;
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

/** g(v) of (E2) with the limits of MODEL.md §2 at v = 0 (dynamics.common._g). */
function g(v, p) {
  const av = Math.abs(v);
  if (av === 0.0) return p.delta > 0 ? p.Fs : p.Fc;
  return p.Fc + (p.Fs - p.Fc) * Math.exp(-((av / p.V) ** p.delta));
}

/** f(z) of (E4) (presliding.shape_scalar). */
function shape(z) {
  if (z >= 1.0) return 1.0;
  return z > 0.0 ? z * (1.0 - Math.log(z)) : 0.0;
}

// the model (ramp_model.py): y = [x, v]; mem = [x_r, F_r, d]
function force(t, y, p, mem) {
  const z = p.s * Math.abs(y[0] - mem[0]);
  const target = mem[2] * g(y[1], p) + p.sigma * y[1];
  return mem[1] + (target - mem[1]) * shape(z);
}

function rhs(t, y, p, mem, dy) {
  dy[0] = y[1];
  dy[1] = (p.k * t - force(t, y, p, mem)) / p.m;
}

function jump(t, y, p, mem) {
  const F = force(t, y, p, mem);
  mem[0] = y[0];
  mem[1] = F;
  mem[2] = -mem[2];
}

const EVENT_STOP = 0;
const EVENT_GUARD = 1;

function event(which, t, y, p, mem) {
  if (which === EVENT_STOP) return -(mem[2] > 0 ? p.s * Math.abs(y[0] - mem[0]) - p.z_ba : -1.0);
  return y[1] * mem[2];
}

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

/** integrator._first_crossing: the first θ in (0, thetaMax] where event `which` passes
 *  from >= 0 to < 0 along the interpolant, the state there left in `work`; -1 if none. */
function firstCrossing(which, t0, y0, f0, y1, f1, h, p, mem, work, thetaMax, scan) {
  let lo = 0.0;
  if (event(which, t0, y0, p, mem) < 0) return -1.0;
  const points = scan ? SCAN_POINTS : 1;
  let hi = 0.0;
  let found = false;
  for (let j = 1; j <= points; j += 1) {
    hi = (thetaMax * j) / points;
    if (hi === 1.0) work.set(y1);
    else hermite(y0, f0, y1, f1, h, hi, work);
    if (event(which, t0 + hi * h, work, p, mem) < 0) {
      found = true;
      break;
    }
    lo = hi;
  }
  if (!found) return -1.0;
  for (let i = 0; i < 60; i += 1) {
    const mid = 0.5 * (lo + hi);
    hermite(y0, f0, y1, f1, h, mid, work);
    if (event(which, t0 + mid * h, work, p, mem) >= 0) lo = mid;
    else hi = mid;
    if (hi - lo < 1e-15) break;
  }
  hermite(y0, f0, y1, f1, h, hi, work);
  return hi;
}

/** One presliding ramp run recorded at every accepted step and reversal
 *  (runs.simulate_trajectory); null when it needs more than `maxSteps` steps. */
function trajectory(p, maxSteps) {
  const tEnd = 20.0 * (Math.max(p.Fs, p.Fc) / p.k + ((6.0 * p.m) / (p.s * p.k)) ** (1.0 / 3.0));
  const atol = [1e-3 * RTOL * (1.0 / p.s), 1e-3 * RTOL * (p.k / (p.s * p.Fc))];
  const hMax = tEnd * H_MAX_FRACTION;
  const y = new Float64Array(2);
  const mem = new Float64Array([0.0, 0.0, 1.0]);
  const [k1, k2, k3, k4, k5, k6, k7, ytmp, ynew, work] = Array.from({ length: 10 },
    () => new Float64Array(2));
  const rec = { t: [], x: [], v: [], F: [] };
  const record = (t) => {
    rec.t.push(t); rec.x.push(y[0]); rec.v.push(y[1]); rec.F.push(force(t, y, p, mem));
  };
  let t = 0.0;
  let h = Math.min(hMax, tEnd * 1e-6);
  let reversals = 0;
  rhs(t, y, p, mem, k1);
  record(t);
  for (let step = 0; step < maxSteps; step += 1) {
    if (t >= tEnd) return { ...rec, t_ba: null, F_ba: null, reversals };
    h = Math.min(h, hMax, tEnd - t);
    for (let i = 0; i < 2; i += 1) ytmp[i] = y[i] + h * A21 * k1[i];
    rhs(t + C2 * h, ytmp, p, mem, k2);
    for (let i = 0; i < 2; i += 1) ytmp[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
    rhs(t + C3 * h, ytmp, p, mem, k3);
    for (let i = 0; i < 2; i += 1) ytmp[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
    rhs(t + C4 * h, ytmp, p, mem, k4);
    for (let i = 0; i < 2; i += 1) {
      ytmp[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
    }
    rhs(t + C5 * h, ytmp, p, mem, k5);
    for (let i = 0; i < 2; i += 1) {
      ytmp[i] = y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
    }
    rhs(t + h, ytmp, p, mem, k6);
    for (let i = 0; i < 2; i += 1) {
      ynew[i] = y[i] + h * (B1 * k1[i] + B3 * k3[i] + B4 * k4[i] + B5 * k5[i] + B6 * k6[i]);
    }
    rhs(t + h, ynew, p, mem, k7);
    let norm = 0.0;
    for (let i = 0; i < 2; i += 1) {
      const e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
      const scale = atol[i] + RTOL * Math.max(Math.abs(y[i]), Math.abs(ynew[i]));
      norm += (e / scale) ** 2;
    }
    norm = Math.sqrt(norm / 2);
    if (!(norm <= 1.0)) {
      h *= norm === norm ? Math.max(0.2, 0.9 * norm ** -0.2) : 0.2;
      continue;
    }
    // accepted step [t, t + h]: the earlier of break-away and reversal wins
    const thetaJump = firstCrossing(EVENT_GUARD, t, y, k1, ynew, k7, h, p, mem, ytmp, 1.0, true);
    const thetaEnd = thetaJump >= 0 ? thetaJump : 1.0;
    // s·|x − x_r| only grows until the next reversal: one look at the end replaces the scan
    const thetaStop = firstCrossing(EVENT_STOP, t, y, k1, ynew, k7, h, p, mem, work, thetaEnd, false);
    if (thetaStop >= 0) {
      const tStop = t + thetaStop * h;
      y.set(work);
      const F = force(tStop, y, p, mem);
      record(tStop);
      return { ...rec, t_ba: tStop, F_ba: F, reversals };
    }
    if (thetaJump >= 0) {
      t += thetaJump * h;
      y.set(ytmp);
      jump(t, y, p, mem);
      reversals += 1;
      record(t);
      rhs(t, y, p, mem, k1);
      // the new branch starts with an infinite presliding stiffness: restart small
      h = Math.max(h * 1e-3, 1e-14 * Math.max(t, 1.0));
      continue;
    }
    t += h;
    y.set(ynew);
    k1.set(k7);
    record(t);
    h *= Math.min(5.0, 0.9 * Math.max(norm, 1e-10) ** -0.2);
  }
  return null;
}

/** numpy's round: halves to even. */
function roundHalfEven(value) {
  const floor = Math.floor(value);
  const diff = value - floor;
  if (diff > 0.5) return floor + 1;
  if (diff < 0.5) return floor;
  return floor % 2 === 0 ? floor : floor + 1;
}

/** ramp._thin: the indices of at most `maxPoints` samples, evenly, first and last kept. */
function thin(n, maxPoints) {
  if (n <= maxPoints) return Array.from({ length: n }, (_, i) => i);
  const step = (n - 1) / (maxPoints - 1);
  const keep = [];
  for (let i = 0; i < maxPoints; i += 1) {
    const index = roundHalfEven(i === maxPoints - 1 ? n - 1 : i * step);
    if (!keep.length || keep[keep.length - 1] !== index) keep.push(index);
  }
  return keep;
}

/** z = s·|x − x_r| along the run (ramp.presliding_z): x_r where ẋ last changed sign. */
function preslidingZ(x, v, s) {
  const z = new Array(x.length);
  let previous = 0;
  let xr = 0.0;
  for (let i = 0; i < x.length; i += 1) {
    const sign = Math.sign(v[i]);
    if (sign !== 0) {
      if (previous !== 0 && sign !== previous) xr = x[i];
      previous = sign;
    }
    z[i] = s * Math.abs(x[i] - xr);
  }
  return z;
}

/** The checks the server makes before a run (params.check_stribeck, check_positive,
 *  check_fraction): a body that fails them goes to the server, which says which field. */
function valid(p) {
  const finite = [p.k, p.Fc, p.Fs, p.V, p.delta, p.sigma, p.s, p.m, p.z_ba].every(Number.isFinite);
  return finite && p.k > 0 && p.Fc > 0 && p.Fs >= p.Fc && p.V > 0 && p.delta !== 0
    && p.sigma >= 0 && p.s > 0 && p.m > 0 && p.z_ba > 0 && p.z_ba < 1
    && ["Fc", "Fs", "avg", "self"].includes(p.F_hat);
}

/**
 * The ramp experiment of the presliding model at rate p.k (ramp.ramp_experiment), for
 * `p` = the body of POST /api/ramp ({k, Fc, Fs, V, delta, sigma, s, m, z_ba, F_hat}), or
 * null when the run needs more than `maxSteps` steps or the body fails the server's checks.
 */
export function rampExperiment(p, maxSteps = LIVE_MAX_STEPS) {
  if (!valid(p)) return null;
  const run = trajectory(p, maxSteps);
  if (!run) return null;
  const z = preslidingZ(run.x, run.v, p.s);
  const keep = thin(run.t.length, MAX_POINTS);
  const pick = (values) => keep.map((i) => values[i]);
  return {
    t: pick(run.t), x: pick(run.x), v: pick(run.v), u: pick(run.t).map((t) => p.k * t),
    F: pick(run.F), z: pick(z),
    t_ba: run.t_ba, u_ba: run.t_ba == null ? null : p.k * run.t_ba, F_ba: run.F_ba,
    E13: breakawayForce(p.k, p),
    reversals: run.reversals,
    model: "presliding", k: p.k,
    params: Object.fromEntries(["Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba", "F_hat"]
      .map((name) => [name, p[name]])),
  };
}
