// The model's curves computed in the page, for the frames drawn while a hand moves a
// slider: the same frame as POST /api/explore (backend/breakaway/frame.py), from the
// same formulas, step by step as the Python model does them (the note's E2–E13):
//   Stribeck curve (E2), the presliding loop (E4, E6'), the phase family (E12) and the
//   break-away curves (E13) for every F̂, the self-consistent one by the same root
//   search. tests/browser/test_browser_model_js.py holds it to the Python functions
//   (relative 1e-12). The server's frame stays the one the settled plots are drawn from.

/** The steady levels F̂ E12 and E13 may be read with (params.F_HAT_CHOICES). */
export const F_HAT_CHOICES = ["Fc", "Fs", "avg", "self"];

/** The frame's grids (frame.py FRAME_GRID and its defaults). */
export const GRID = {
  stribeck: 400, loop: 2000, phase: 200, breakaway: 200,
  loopAmplitude: 1.5, zMax: 0.99, kMin: 0.01, kMax: 30,
};
/** The note's Fig. 3 rates [N/s] (params.FIG3_RATES). */
export const FIG3_RATES = Array.from({ length: 15 }, (_, i) => 0.01 + 2.0 * i);
/** Turning points of the loop's excitation in amplitudes (presliding.LOOP_TURNING_POINTS). */
const LOOP_TURNING_POINTS = [0.0, 1.0, -1.0, 1.0, 0.2, 0.6, 0.2, 1.0, -1.0];
const SELF_BRACKET_POINTS = 48;
const SELF_BISECTIONS = 40;
const SELF_NEWTON_STEPS = 30;

/** numpy.linspace(start, stop, n): start + i·step, the last point exactly `stop`. */
export function linspace(start, stop, n) {
  const out = new Array(n);
  const step = (stop - start) / (n - 1);
  for (let i = 0; i < n; i += 1) out[i] = i * step + start;
  if (n > 1) out[n - 1] = stop;
  return out;
}

/** g(v) of (E2) [N]: Fc + (Fs − Fc)·exp(−(|v|/V)^δ); the limits at v = 0 as numpy gives. */
export function stribeckMagnitude(v, p) {
  return p.Fc + (p.Fs - p.Fc) * Math.exp(-((Math.abs(v) / p.V) ** p.delta));
}

/** Fss(v) of (E2) [N]: sgn(v)·g(v) + σ·v. */
export function steadyForce(v, p) {
  return Math.sign(v) * stribeckMagnitude(v, p) + p.sigma * v;
}

/** ln y beyond which y = (v/V)^δ is not formed (quasistatic._LOG_Y_MAX). */
const LOG_Y_MAX = 700.0;

/** h(v) = v·Fss(v) and h'(v) for v > 0 (quasistatic._work_and_slope): y·e^(−y) as
 *  exp(ln y − y), which a large |δ| does not turn into 0·Infinity. */
function workAndSlope(v, p) {
  const logY = p.delta * (Math.log(v) - Math.log(p.V));
  const y = Math.exp(Math.min(logY, LOG_Y_MAX));
  const decay = (p.Fs - p.Fc) * Math.exp(-y);
  const g = p.Fc + decay;
  return [v * g + p.sigma * v * v, g - (p.Fs - p.Fc) * p.delta * Math.exp(logY - y) + 2 * p.sigma * v];
}

function workIsIncreasing(p) {
  return p.delta < 0 || p.Fc > (p.Fs - p.Fc) * p.delta * Math.exp(-1.0 - 1.0 / p.delta);
}

/** Smallest positive root ẋ of ẋ·Fss(ẋ) = c, c > 0 (quasistatic._self_consistent_velocity). */
export function selfConsistentVelocity(c, p) {
  const gLo = Math.min(p.Fc, p.Fs);
  const gHi = Math.max(p.Fc, p.Fs);
  let lo = p.sigma > 0 ? (2 * c) / (gHi + Math.sqrt(gHi ** 2 + 4 * p.sigma * c)) : c / gHi;
  let hi = c / gLo;
  if (workIsIncreasing(p)) {
    // Newton kept inside a bracket that shrinks every step (_bracketed_newton)
    let v = 0.5 * (lo + hi);
    for (let i = 0; i < SELF_NEWTON_STEPS; i += 1) {
      const [h, slope] = workAndSlope(v, p);
      if (h >= c) hi = v; else lo = v;
      const step = v - (h - c) / slope;
      const next = step >= lo && step <= hi ? step : 0.5 * (lo + hi);
      if (Math.abs(next - v) <= 1e-14 * v) return next;
      v = next;
    }
    return v;
  }
  // ẋ·Fss(ẋ) may turn back: the first grid point at or above c, then bisection
  let first = SELF_BRACKET_POINTS - 1;
  const grid = linspace(0.0, 1.0, SELF_BRACKET_POINTS);
  for (let i = 0; i < SELF_BRACKET_POINTS; i += 1) {
    const v = lo + (hi - lo) * grid[i];
    if (workAndSlope(Math.max(v, 1e-300), p)[0] - c >= 0) {
      first = i;
      break;
    }
  }
  first = Math.max(first, 1);
  let a = lo + (hi - lo) * grid[first - 1];
  let b = lo + (hi - lo) * grid[first];
  for (let i = 0; i < SELF_BISECTIONS; i += 1) {
    const mid = 0.5 * (a + b);
    if (workAndSlope(mid, p)[0] >= c) b = mid; else a = mid;
  }
  return 0.5 * (a + b);
}

/** ẋ = c/F̂ with c = k/(s·|ln z|) (E12), F̂ one of Fc, Fs, avg, self. */
function e12Velocity(c, p, fHat) {
  if (fHat === "self") return c > 0 ? selfConsistentVelocity(c, p) : 0;
  // a conditional, not a lookup in an object literal: this runs for every point of
  // every break-away and phase curve of a live frame, and an object a call was the
  // largest part of what a drag gave the garbage collector
  const level = fHat === "Fc" ? p.Fc : fHat === "Fs" ? p.Fs : p.Fc + (p.Fs - p.Fc) / 2;
  return c / level;
}

/** c = k/(s·(−ln z)) of (E12), 0 at z = 0. */
function e12Work(z, k, s) {
  return z > 0 ? k / (s * -Math.log(z)) : 0.0;
}

/** f(z) = z(1 − ln z) (E4); 0 at 0, 1 from z = 1 on. */
export function shape(z) {
  if (z >= 1.0) return 1.0;
  return z > 0.0 ? z * (1.0 - Math.log(z)) : 0.0;
}

/** numpy.gradient(f, t) for strictly increasing t (second order inside, first at the ends). */
function gradient(f, t) {
  const n = f.length;
  const out = new Array(n);
  out[0] = (f[1] - f[0]) / (t[1] - t[0]);
  out[n - 1] = (f[n - 1] - f[n - 2]) / (t[n - 1] - t[n - 2]);
  for (let i = 1; i < n - 1; i += 1) {
    const dx1 = t[i] - t[i - 1];
    const dx2 = t[i + 1] - t[i];
    const a = -dx2 / (dx1 * (dx1 + dx2));
    const b = (dx2 - dx1) / (dx1 * dx2);
    const c = dx1 / (dx2 * (dx1 + dx2));
    out[i] = a * f[i - 1] + b * f[i] + c * f[i + 1];
  }
  return out;
}

/** d_i of (E5): the sign of the last non-zero step (presliding.motion_direction). */
function motionDirection(x) {
  const n = x.length;
  const d = new Array(n);
  let first = 1;
  for (let i = 1; i < n; i += 1) {
    const step = Math.sign(x[i] - x[i - 1]);
    if (step !== 0) {
      first = step;
      break;
    }
  }
  d[0] = first;
  for (let i = 1; i < n; i += 1) d[i] = Math.sign(x[i] - x[i - 1]) || d[i - 1];
  return d;
}

/** The loop of the note's Fig. 1 under the frame's excitation (presliding.hysteresis_loop). */
export function hysteresisLoop(p, amplitude = GRID.loopAmplitude, n = GRID.loop) {
  const points = LOOP_TURNING_POINTS.map((value) => (value * amplitude) / p.s);
  const last = points.length - 1;
  const phase = linspace(0.0, last, n);
  const speed = 0.1 * p.V;
  const durations = [];
  for (let i = 0; i < last; i += 1) {
    const duration = ((Math.PI / 2) * Math.abs(points[i + 1] - points[i])) / speed;
    durations.push(duration > 0 ? duration : 1.0);
  }
  const starts = [0.0];
  for (const duration of durations) starts.push(starts[starts.length - 1] + duration);
  const x = new Array(n);
  const t = new Array(n);
  for (let i = 0; i < n; i += 1) {
    const segment = Math.min(Math.trunc(phase[i]), last - 1);
    const frac = phase[i] - segment;
    const start = points[segment];
    const stop = points[segment + 1];
    x[i] = start + (stop - start) * 0.5 * (1.0 - Math.cos(Math.PI * frac));
    t[i] = starts[segment] + frac * durations[segment] + i * 1e-12;
  }
  const v = gradient(x, t);
  const d = motionDirection(x);
  const F = new Array(n);
  let xr = x[0];
  let Fr = 0.0;
  for (let i = 0; i < n; i += 1) {
    if (i > 0 && d[i] !== d[i - 1]) {
      xr = x[i - 1];
      Fr = F[i - 1];
    }
    const target = d[i] * stribeckMagnitude(v[i], p) + p.sigma * v[i];
    F[i] = Fr + (target - Fr) * shape(p.s * Math.abs(x[i] - xr));
  }
  return { x, F };
}

/** The quasi-static break-away velocity ẋ(z*) of (E12) [m/s] with F̂ = `fHat`
 *  (quasistatic.breakaway_velocity). */
export function breakawayVelocity(k, p, fHat = p.F_hat) {
  return e12Velocity(e12Work(p.z_ba, k, p.s), p, fHat);
}

/** The quasi-static break-away force F_ba(k) = Fss(ẋ(z*)) of (E13) [N] with F̂ = `fHat`
 *  (quasistatic.breakaway_force). */
export function breakawayForce(k, p, fHat = p.F_hat) {
  return steadyForce(breakawayVelocity(k, p, fHat), p);
}

/** The last value of each part of a frame, by the parameters it depends on: a slider
 *  moves some parts only (k the current phase curve, s the loop and the phase family, V
 *  the Stribeck and break-away curves), and a live frame recomputes only those. */
const parts = {};

function part(name, key, compute) {
  const last = parts[name];
  if (last && last.key === key) return last.value;
  const value = compute();
  parts[name] = { key, value };
  return value;
}

/**
 * Every curve of one explorer redraw for the parameters `p` ({Fc, Fs, V, delta, sigma,
 * s, z_ba, k, F_hat}, numbers already valid): the shape of the /api/explore answer. A
 * part equal to the last frame's is that frame's (the same arrays).
 */
export function modelFrame(p) {
  const steady = [p.Fc, p.Fs, p.V, p.delta, p.sigma].join();
  const z = part("z", "", () => linspace(0.0, GRID.zMax, GRID.phase));
  const curve = (k) => ({ k, v: z.map((zi) => e12Velocity(e12Work(zi, k, p.s), p, p.F_hat)) });
  const reading = `${steady},${p.s},${p.F_hat}`;
  const family = part("family", reading, () => FIG3_RATES.map(curve));
  const current = part("current", `${reading},${p.k}`, () => curve(Number(p.k)));
  return {
    stribeck: part("stribeck", steady, () => {
      const v = linspace(-5.0 * p.V, 5.0 * p.V, GRID.stribeck);
      return { v, F: v.map((vi) => steadyForce(vi, p)) };
    }),
    hysteresis: part("hysteresis", `${steady},${p.s}`, () => hysteresisLoop(p)),
    phase: part("phase", `${reading},${p.k}`, () => ({ z, curves: [...family, current] })),
    breakaway: part("breakaway", `${steady},${p.s},${p.z_ba}`, () => {
      const kGrid = linspace(GRID.kMin, GRID.kMax, GRID.breakaway);
      const out = { k: kGrid };
      for (const fHat of F_HAT_CHOICES) out[fHat] = kGrid.map((k) => breakawayForce(k, p, fHat));
      return out;
    }),
  };
}
