// The ramp experiment computed in the page, for the frames drawn while a hand moves the
// mass m (the one slider that moves only the ramp): the answer of POST /api/ramp for the
// presliding model (backend/breakaway/ramp.py), from the same integrator step by step
// (integrator.js) and the same model (ramp_model.py: E7 with E6').
// tests/browser/test_browser_rampmodel_js.py holds it to the Python run. A run that
// needs more than LIVE_MAX_STEPS steps (a chattering stick at a small rate) is left to
// the server: null.

import {
  EVENT_REVERSAL, RTOL, STATUS_END, STATUS_STEP_LIMIT, integrate, preslidingForce, validStribeck,
} from "./integrator.js";
import { F_HAT_CHOICES, breakawayForce } from "./model.js";

/** Steps the page integrates at most for one live frame (a few ms); beyond, the server. */
export const LIVE_MAX_STEPS = 20_000;
/** Samples of the answer at most (ramp.MAX_POINTS). */
const MAX_POINTS = 2000;

/** The ramp experiment's model (ramp_model.py): y = [x, v]; mem = [x_r, F_r, d]; the
 *  run stops where the presliding fraction reaches z* moving forward. */
function rampModel(p) {
  const mem = new Float64Array([0.0, 0.0, 1.0]); // virgin: x_r = 0, F_r = 0, d = +1
  const force = (t, y) => preslidingForce(y, p, mem);
  return {
    n: 2,
    mem,
    rhs: (t, y, dy) => {
      dy[0] = y[1];
      dy[1] = (p.k * t - force(t, y)) / p.m;
    },
    force,
    guard: (t, y) => y[1] * mem[2],
    jump: (t, y) => {
      // a change of sign of ẋ: new branch at the current x and F
      const F = force(t, y);
      mem[0] = y[0];
      mem[1] = F;
      mem[2] = -mem[2];
      return EVENT_REVERSAL;
    },
    stop: (t, y) => (mem[2] > 0 ? p.s * Math.abs(y[0] - mem[0]) - p.z_ba : -1.0),
    stopRises: true,
  };
}

/** One presliding ramp run recorded at every accepted step and reversal
 *  (runs.simulate_trajectory); null when it needs more than `maxSteps` steps. */
function trajectory(p, maxSteps) {
  const tEnd = 20.0 * (Math.max(p.Fs, p.Fc) / p.k + ((6.0 * p.m) / (p.s * p.k)) ** (1.0 / 3.0));
  const atol = [1e-3 * RTOL * (1.0 / p.s), 1e-3 * RTOL * (p.k / (p.s * p.Fc))];
  const model = rampModel(p);
  const rec = { t: [], x: [], v: [], F: [] };
  const record = (t, y) => {
    rec.t.push(t); rec.x.push(y[0]); rec.v.push(y[1]); rec.F.push(model.force(t, y));
  };
  const run = integrate(model, new Float64Array(2), { tEnd, atol, maxSteps, record });
  if (run.status === STATUS_STEP_LIMIT) return null;
  const broke = run.status !== STATUS_END;
  return { ...rec, t_ba: broke ? run.t : null, F_ba: broke ? run.F : null, reversals: run.jumps };
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
  return validStribeck(p) && [p.k, p.s, p.m].every((value) => Number.isFinite(value) && value > 0)
    && p.z_ba > 0 && p.z_ba < 1 && F_HAT_CHOICES.includes(p.F_hat);
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
