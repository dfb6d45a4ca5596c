// The PID position loop on the model's friction computed in the page, for the frames drawn while a
// hand moves a slider with the loop's card on the screen: the answer of POST /api/loop
// for the presliding plant (backend/breakaway/loop.py), from the same integrator step by
// step (integrator.js) and the same model (dynamics/loop_model.py):
//   m·ẍ + F(ẋ, z) = u,   u = Kp·e + Ki·∫e dt + Kd·(ṙ − ẋ) + c·F_m(ṙ),   e = r − x,
// clamped to |u| ≤ u_max. tests/browser/test_browser_loopmodel_js.py holds it to the
// Python run. A run over LIVE_MAX_STEPS steps is left to the server: null.

import {
  EVENT_BREAKAWAY, EVENT_COMPENSATION, EVENT_REVERSAL, EVENT_STICK, RTOL, STATUS_STEP_LIMIT,
  STATUS_STOP, gBranch, integrate, preslidingForce, validStribeck,
} from "./integrator.js";
import { F_HAT_CHOICES, breakawayForce } from "./model.js";

/** The series of a run's answer, one value per recorded time (POST /api/loop's). */
export const LOOP_SERIES = ["t", "r", "x", "v", "u", "F", "e"];
/** Steps the page integrates at most for one live frame (about 10 ms); beyond, the server. */
export const LIVE_MAX_STEPS = 40_000;
/** loop_model.RUNAWAY_FACTOR: |e| beyond this many reference scales ends the run. */
const RUNAWAY_FACTOR = 100.0;
/** The server's limit on sine periods in a run (loop_schemas.MAX_SINE_PERIODS). */
const MAX_SINE_PERIODS = 200;

/** r(t) [m] and ṙ(t) [m/s] of the reference (loop_model._reference), written into
 *  `at` ({r, rDot}): the right-hand side asks seven times a step, so nothing is made. */
function referenceAt(t, ref, at) {
  if (ref.kind === "step") {
    at.r = ref.h;
    at.rDot = 0.0;
  } else if (ref.kind === "ramp") {
    at.r = ref.w * t;
    at.rDot = ref.w;
  } else {
    const omega = 2.0 * Math.PI * ref.f;
    at.r = ref.h * Math.sin(omega * t);
    at.rDot = ref.h * omega * Math.cos(omega * t);
  }
  return at;
}

/** The loop's model (loop_model.py with E6'): y = [x, v, ∫e]; mem = [x_r, F_r, d, sr,
 *  broken, sticking, reversals]. */
function loopModel(plant, ctl, ref, comp, runaway) {
  const sr = { step: 0.0, ramp: Math.sign(ref.w) || 1, sine: Math.sign(ref.h) || 1 }[ref.kind];
  const mem = new Float64Array([0.0, 0.0, 1.0, sr, 0.0, 1.0, 0.0]);
  const uMax = ctl.u_max == null ? Infinity : ctl.u_max;
  const force = (t, y) => preslidingForce(y, plant, mem);
  const { Kp, Ki, Kd } = ctl;
  const { scale, params: q } = comp;
  const fraction = (y) => plant.s * Math.abs(y[0] - mem[0]);
  const at = { r: 0.0, rDot: 0.0 };
  let u = 0.0; // the controller's force at the right-hand side's last state
  const rhs = (t, y, dy) => {
    referenceAt(t, ref, at);
    // u written here, not in a function of its own: the right-hand side is inlined into
    // the integrator seven times a step, and a call left out of it cost a seventh of a run
    u = Kp * (at.r - y[0]) + Ki * y[2] + Kd * (at.rDot - y[1]);
    if (scale !== 0.0 && mem[3] !== 0.0) {
      u += scale * (mem[3] * gBranch(mem[3] * at.rDot, q.Fc, q.Fs, q.V, q.delta) + q.sigma * at.rDot);
    }
    u = Math.min(Math.max(u, -uMax), uMax);
    dy[0] = y[1];
    dy[1] = (u - force(t, y)) / plant.m;
    dy[2] = at.r - y[0];
  };
  const scratch = new Float64Array(3);
  return {
    n: 3,
    mem,
    /** u [N] at (t, y): PID with the derivative on ṙ − ẋ, plus c·F_m(ṙ) on the
     *  compensation's branch, clamped to ±u_max (loop_model._control). */
    control: (t, y) => {
      rhs(t, y, scratch);
      return u;
    },
    force,
    rhs,
    guard: (t, y) => {
      let value = y[1] * mem[2];
      if (ref.kind === "sine") value = Math.min(value, referenceAt(t, ref, at).rDot * mem[3]);
      if (mem[4] === 0.0) value = Math.min(value, plant.z_ba - fraction(y));
      return value;
    },
    jump: (t, y) => {
      const z = fraction(y);
      const F = force(t, y);
      let code = 0;
      if (mem[4] === 0.0 && z >= plant.z_ba) {
        mem[4] = 1.0;
        mem[5] = 0.0;
        code |= EVENT_BREAKAWAY;
      }
      if (y[1] * mem[2] < 0) {
        mem[0] = y[0];
        mem[1] = F;
        mem[2] = -mem[2];
        mem[4] = 0.0;
        mem[6] += 1.0;
        code |= EVENT_REVERSAL;
        if (mem[5] === 0.0) {
          mem[5] = 1.0;
          code |= EVENT_STICK;
        }
      }
      if (ref.kind === "sine" && referenceAt(t, ref, at).rDot * mem[3] < 0) {
        mem[3] = -mem[3];
        code |= EVENT_COMPENSATION;
      }
      return code;
    },
    stop: (t, y) => Math.abs(referenceAt(t, ref, at).r - y[0]) - runaway,
    stopRises: true,
  };
}

/** The stick phases of a run (loop.stick_phases): from t = 0 or the first reversal after
 *  a break-away to the next break-away, with the mean rate of u towards it. */
function stickPhases(run) {
  const phases = [];
  let start = 0;
  for (let i = 0; i < run.code.length; i += 1) {
    const code = run.code[i];
    if (!(code & (EVENT_BREAKAWAY | EVENT_STICK))) continue;
    if ((code & EVENT_BREAKAWAY) && start !== null) {
      const direction = run.v[i] < 0 ? -1 : 1;
      phases.push({
        t_start: run.t[start], t_ba: run.t[i], u_start: run.u[start], u_ba: run.u[i],
        F_ba: run.F[i], direction,
        k: (direction * (run.u[i] - run.u[start])) / (run.t[i] - run.t[start]),
      });
      start = null;
    }
    if (code & EVENT_STICK) start = i;
  }
  return phases;
}

const finiteOrNull = (value) => (Number.isFinite(value) ? value : null);

/** Hunting over the run's last half (loop.hunting), or null when the loop settles. */
function hunting(phases, t, e, tEnd) {
  const late = phases.filter((phase) => phase.t_ba >= 0.5 * tEnd);
  if (late.length < 2) return null;
  const times = late.map((phase) => phase.t_ba);
  const spacing = (values) => values.slice(1).map((value, i) => value - values[i]);
  const mean = (values) => values.reduce((a, b) => a + b, 0) / values.length;
  const same = [-1, 1].flatMap((side) => spacing(late.filter((phase) => phase.direction === side)
    .map((phase) => phase.t_ba)));
  const tail = e.filter((_, i) => t[i] >= 0.5 * tEnd);
  return {
    period: mean(spacing(times)),
    amplitude: tail.length ? 0.5 * (Math.max(...tail) - Math.min(...tail)) : NaN,
    count: times.length,
    cycle: same.length ? mean(same) : null,
  };
}

/** RMS of e on the grid, sqrt(∫e² dt / T) by trapezoids (loop.rms_error). */
function rmsError(t, e) {
  const n = t.length;
  if (n < 2 || t[n - 1] <= t[0]) return NaN;
  let area = 0.0;
  for (let i = 1; i < n; i += 1) area += ((e[i] * e[i] + e[i - 1] * e[i - 1]) / 2) * (t[i] - t[i - 1]);
  return Math.sqrt(area / (t[n - 1] - t[0]));
}

/** The body of POST /api/loop resolved as the server resolves it (loop_schemas), with
 *  `defaults` ({h, w, f} of the reference, duration) and 2000 points unless it says, or
 *  null when the server would refuse it (it then says which field). */
function resolve(body, defaults) {
  const plant = { z_ba: 0.95 };
  for (const name of ["Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba"]) {
    if (body[name] != null) plant[name] = body[name];
  }
  const ctl = { u_max: null, ...body.controller };
  const given = body.reference ?? {};
  const ref = { kind: given.kind ?? "step" };
  for (const name of ["h", "w", "f"]) ref[name] = given[name] ?? defaults[name];
  const duration = body.duration ?? defaults.duration;
  const steady = { Fc: plant.Fc, Fs: plant.Fs, V: plant.V, delta: plant.delta, sigma: plant.sigma };
  const comp = { scale: body.compensation?.scale ?? 0, params: { ...steady, ...(body.compensation?.params ?? {}) } };
  const F_hat = body.F_hat ?? "avg";
  const ok = validStribeck(plant) && validStribeck(comp.params)
    && [plant.s, plant.m, duration].every((value) => Number.isFinite(value) && value > 0)
    && plant.z_ba > 0 && plant.z_ba < 1 && F_HAT_CHOICES.includes(F_hat)
    && [ctl.Kp, ctl.Ki, ctl.Kd, comp.scale].every((value) => Number.isFinite(value) && value >= 0)
    && (ctl.u_max === null || (Number.isFinite(ctl.u_max) && ctl.u_max > 0))
    && ["step", "ramp", "sine"].includes(ref.kind)
    && (ref.kind === "ramp" ? Number.isFinite(ref.w) && ref.w !== 0 : Number.isFinite(ref.h) && ref.h !== 0)
    && (ref.kind !== "sine" || (ref.f > 0 && ref.f * duration <= MAX_SINE_PERIODS));
  if (!ok) return null;
  const points = body.points ?? 2000;
  if (!(Number.isInteger(points) && points >= 10 && points <= 5000)) return null;
  return { plant, ctl, ref, duration, comp, F_hat, points };
}

/**
 * One run of the position loop with everything the loop view shows (loop.loop_experiment),
 * for `body` = the body of POST /api/loop with the presliding plant, the missing fields
 * from `defaults` ({h, w, f, duration}, the server's); null when the run needs
 * more than `maxSteps` steps or the server would refuse the body.
 */
export function loopExperiment(body, defaults, maxSteps = LIVE_MAX_STEPS) {
  if ((body.model ?? "presliding") !== "presliding") return null;
  const run = resolve(body, defaults);
  if (!run) return null;
  const { plant, ctl, ref, duration, comp, F_hat, points } = run;
  const travel = 1.0 / plant.s;
  const level = Math.max(plant.Fc, plant.Fs);
  const timeScale = Math.sqrt((plant.m * travel) / level);
  // every size of the resolved reference counts, whatever its kind (loop_problem)
  const scale = Math.abs(ref.h) + Math.abs(ref.w) * duration + travel;
  const model = loopModel(plant, ctl, ref, comp, RUNAWAY_FACTOR * scale);
  const atol = [travel, travel / timeScale, ctl.Ki > 0 ? level / ctl.Ki : travel * timeScale]
    .map((value) => 1e-3 * RTOL * value);
  const out = { ...Object.fromEntries(LOOP_SERIES.map((name) => [name, []])), code: [] };
  const at = { r: 0.0, rDot: 0.0 };
  const record = (t, y, code) => {
    const { r } = referenceAt(t, ref, at);
    out.t.push(t); out.r.push(r); out.x.push(y[0]); out.v.push(y[1]);
    out.u.push(model.control(t, y)); out.F.push(model.force(t, y));
    out.e.push(r - y[0]); out.code.push(code);
  };
  const end = integrate(model, new Float64Array(3), {
    tEnd: duration, atol, maxSteps, record, nGrid: points, eventMask: EVENT_BREAKAWAY | EVENT_STICK,
  });
  if (end.status === STATUS_STEP_LIMIT) return null;
  const runaway = end.status === STATUS_STOP;
  const phases = stickPhases(out);
  const grid = out.code.map((code) => code === 0);
  const gridT = out.t.filter((_, i) => grid[i]);
  const gridE = out.e.filter((_, i) => grid[i]);
  const steady = { ...plant, F_hat };
  const stickRows = phases.map((phase) => ({
    t_start: finiteOrNull(phase.t_start), t_ba: finiteOrNull(phase.t_ba), k: finiteOrNull(phase.k),
    u_ba: finiteOrNull(phase.u_ba), u_start: finiteOrNull(phase.u_start),
    F_ba: finiteOrNull(phase.F_ba), direction: phase.direction,
    E13: Number.isFinite(phase.k) && phase.k > 0
      ? finiteOrNull(phase.direction * breakawayForce(phase.k, steady, F_hat)) : null,
  }));
  const { code: _code, ...series } = out;
  return {
    ...series,
    stick_phases: stickRows,
    hunting: runaway ? null : hunting(phases, gridT, gridE, end.t),
    rms_error: finiteOrNull(rmsError(gridT, gridE)),
    t_end: end.t, runaway, reversals: model.mem[6],
    model: "presliding", controller: ctl, reference: ref, duration,
    compensation: comp, F_hat, params: plant,
  };
}
