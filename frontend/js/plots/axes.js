// Axis ranges and ticks as Plotly computes them (plotly.js: autorange.js getAutoRange
// and findExtremes, axes.js prepTicks, autoTicks, tickFirst, numFormat, formatLog),
// for the frames the page draws itself while a hand moves (livedraw.js): the range,
// the tick values and their labels must be Plotly's, so that nothing jumps when Plotly
// draws the settled plot. Pure functions; tests/browser/test_browser_live.py compares
// them with Plotly's own on every plot.

const MINUS = "\u2212";
const ROUND_BASE10 = [2, 5, 10];
const LOG_DIGITS_D1 = [-0.046, 0, 0.301, 0.477, 0.602, 0.699, 0.778, 0.845, 0.903, 0.954, 1];
const LOG_DIGITS_D2 = [-0.301, 0, 0.301, 0.699, 1];
const SI_PREFIXES = ["f", "p", "n", "\u03BC", "m", "", "k", "M", "G", "T"];
const FP_SAFE = Number.MAX_VALUE * 1e-4;

/** Lib.roundUp: the first entry of the sorted `set` above `value`. */
function roundUp(value, set) {
  let low = 0;
  let high = set.length - 1;
  let count = 0;
  while (low < high && count < 100) {
    const mid = Math.floor((low + high) / 2);
    if (set[mid] <= value) low = mid + 1; else high = mid;
    count += 1;
  }
  return set[low];
}

function mod(value, d) {
  const out = value % d;
  return out < 0 ? out + d : out;
}

/** Whether a trace draws markers (or text), which pads the axes by their size. */
function markerPad(trace) {
  const mode = trace.mode ?? "lines";
  if (!mode.includes("markers")) return 0;
  const size = trace.marker?.size ?? 6;
  const largest = Array.isArray(size) ? Math.max(...size) : size;
  return Math.max(largest / 1.6, 3);
}

/** The lowest and highest value of `values` an axis reaches (log: positive ones only). */
function valueRange(values, log) {
  let lo = Infinity;
  let hi = -Infinity;
  // an index, not an iterator: the curves of a live frame pass here point by point
  for (let i = 0; i < values.length; i += 1) {
    const value = values[i];
    if (value == null || !Number.isFinite(value)) continue;
    if (log ? value > 0 && value < lo : value < lo && value > -FP_SAFE) lo = value;
    if (value > hi && value < FP_SAFE) hi = value;
  }
  return [lo, hi];
}

/** valueRange of long arrays, by array: a live frame's curves that stay are the same
 *  arrays (figures never change an array they were given), and are not read again. */
const ranges = new WeakMap();
const KEPT_FROM = 64;

function keptRange(values, log) {
  if (!Array.isArray(values) || values.length < KEPT_FROM) return valueRange(values, log);
  const kept = ranges.get(values) ?? {};
  ranges.set(values, kept);
  const kind = log ? "log" : "linear";
  kept[kind] ??= valueRange(values, log);
  return kept[kind];
}

/**
 * The autorange of one axis over the visible traces [range in axis units: log10 for a
 * log axis]. `letter` "x" or "y"; `onAxis(trace)` whether the trace belongs to this
 * axis; `length` the axis length [px]; `log` a log axis.
 */
export function autorange(traces, letter, { length, log = false, onAxis = () => true }) {
  const mins = [];
  const maxs = [];
  const add = (list, val, pad, extrapad, better) => {
    for (let i = 0; i < list.length; i += 1) {
      const other = list[i];
      if (better(other.val, val) && other.pad >= pad && (other.extrapad || !extrapad)) return;
      if (better(val, other.val) && other.pad <= pad && (extrapad || !other.extrapad)) {
        list.splice(i, 1);
        i -= 1;
      }
    }
    list.push({ val, pad, extrapad });
  };
  for (const trace of traces) {
    if (!onAxis(trace)) continue;
    const values = trace[letter] ?? [];
    const mode = trace.mode ?? "lines";
    const pad = markerPad(trace);
    // plotly.js scatter: lines alone do not pad x; y is padded by 5 %
    const padded = letter === "y" || mode.includes("markers") || mode.includes("text");
    const [lo, hi] = keptRange(values, log);
    for (const value of [lo, hi]) {
      if (!Number.isFinite(value) || (log && value <= 0)) continue;
      const l = log ? Math.log10(value) : value;
      add(mins, l, pad, padded, (a, b) => a <= b);
      add(maxs, l, pad, padded, (a, b) => a >= b);
    }
  }
  if (!mins.length || !maxs.length) return log ? [0, 1] : [-1, 6];
  const extra = 0.05 * length;
  const padOf = (point) => (point.nopad ? 0 : point.pad + (point.extrapad ? extra : 0));
  let lowest = mins[0].val;
  let highest = maxs[0].val;
  for (let i = 1; i < mins.length && lowest === highest; i += 1) lowest = Math.min(lowest, mins[i].val);
  for (let i = 1; i < maxs.length && lowest === highest; i += 1) highest = Math.max(highest, maxs[i].val);
  if (lowest === highest) return [lowest - 1, lowest + 1];
  let best = 0;
  let minBest = null;
  let maxBest = null;
  for (const lo of mins) {
    for (const hi of maxs) {
      const span = hi.val - lo.val;
      if (span <= 0) continue;
      const room = length - padOf(lo) - padOf(hi);
      if (room > length / 10) {
        if (span / room > best) [minBest, maxBest, best] = [lo, hi, span / room];
      } else if (span / length > best) {
        [minBest, maxBest, best] = [{ val: lo.val, nopad: 1 }, { val: hi.val, nopad: 1 }, span / length];
      }
    }
  }
  best = (maxBest.val - minBest.val) / (length - padOf(minBest) - padOf(maxBest));
  return [minBest.val - best * padOf(minBest), maxBest.val + best * padOf(maxBest)];
}

/** The tick spacing Plotly picks: {dtick, tick0} (dtick "D1", "D2" or "L…" on log axes). */
function autoTicks(range, { letter, length, log }) {
  const count = Math.min(Math.max(length / (letter === "y" ? 40 : 80), 4), 9) + 1;
  let rough = Math.abs(range[1] - range[0]) / count;
  const base = () => 10 ** Math.floor(Math.log(rough) / Math.LN10);
  if (!log) return base() * roundUp(rough / base(), ROUND_BASE10) || 1;
  if (rough > 0.7) return Math.ceil(rough);
  if (Math.abs(range[1] - range[0]) < 1) {
    const n = 1.5 * Math.abs((range[1] - range[0]) / rough);
    rough = Math.abs(10 ** range[1] - 10 ** range[0]) / n;
    return `L${base() * roundUp(rough / base(), ROUND_BASE10)}`;
  }
  return rough > 0.3 ? "D2" : "D1";
}

/** Decimals and exponent of the labels (Plotly's autoTickRound). */
function tickRounding(range, dtick, log, exponentformat) {
  if (typeof dtick === "string" && dtick[0] === "D") return { round: null, exponent: 0 };
  const step = typeof dtick === "string" ? Number(dtick.slice(1)) : dtick;
  const round = 2 - Math.floor(Math.log(step) / Math.LN10 + 0.01);
  const ends = log ? range.map((r) => 10 ** r) : range;
  const largest = Math.max(Math.abs(ends[0]), Math.abs(ends[1]));
  const magnitude = Math.floor(Math.log(largest) / Math.LN10 + 0.01);
  let exponent = 0;
  if (Math.abs(magnitude) > 3) {
    const si = exponentformat === "SI" || exponentformat === "B";
    exponent = si && !(magnitude > 14 || magnitude < -15)
      ? 3 * Math.round((magnitude - 1) / 3) : magnitude;
  }
  return { round, exponent };
}

/** Plotly's numFormat: a tick label's text (HTML-like: <sup> for powers of ten). */
export function formatNumber(value, { round, exponent, exponentformat = "B" }) {
  let negative = value < 0;
  let digits = round;
  let text;
  let v = Math.abs(value);
  if (v < 10 ** -digits / 2) {
    text = "0";
    negative = false;
  } else {
    if (exponent) {
      v *= 10 ** -exponent;
      digits += exponent;
    }
    if (digits === 0) text = String(Math.round(v));
    else if (digits < 0) {
      const unit = 10 ** -digits;
      text = String(Math.round(v / unit) * unit);
    } else text = v.toFixed(Math.min(20, digits)).replace(/\.?0+$/, "");
  }
  if (exponent) {
    let format = exponentformat;
    if ((format === "SI" || format === "B") && (exponent > 14 || exponent < -15)) format = "power";
    const signed = exponent < 0 ? MINUS + -exponent : format !== "power" ? `+${exponent}` : String(exponent);
    if (format === "e" || format === "E") text += format + signed;
    else if (format === "power") text += `\u00D710<sup>${signed}</sup>`;
    else if (format === "B" && exponent === 9) text += "B";
    else if (format === "SI" || format === "B") text += SI_PREFIXES[exponent / 3 + 5];
  }
  return negative ? MINUS + text : text;
}

/**
 * The ticks of an axis: [{value (axis units), text, scale}], `scale` the label's size
 * relative to the tick font (powers of ten 1.25, log digits 0.75). An axis laid over
 * another (`sync`: that axis' range and ticks) takes its ticks where the other's are,
 * as Plotly's tickmode "sync" does for overlaying axes.
 */
export function ticks(range, { letter, length, log = false, exponentformat = "B", sync = null }) {
  const dtick = autoTicks(range, { letter, length, log });
  const { round, exponent } = tickRounding(range, dtick, log, exponentformat);
  const linearLabel = (value) => ({
    value,
    // zero says no exponent, whatever the axis' (Plotly's showexponent "all")
    text: formatNumber(value, {
      round, exponent: Math.abs(value / dtick) < 1e-6 ? 0 : exponent, exponentformat,
    }),
    scale: 1,
  });
  if (sync && !log) {
    // through the pixel, which Plotly rounds to 1/100 (l2p, then p2l of this axis)
    const [s0, s1] = sync.range;
    const [r0, r1] = range;
    return sync.ticks.map((tick) => {
      if (letter === "x") {
        const px = Math.round((((tick.value - s0) * length) / (s1 - s0)) * 100) / 100;
        return linearLabel(r0 + (px * (r1 - r0)) / length);
      }
      const px = Math.round((((s1 - tick.value) * length) / (s1 - s0)) * 100) / 100;
      return linearLabel(r1 - (px * (r1 - r0)) / length);
    });
  }
  const values = tickValues(range, dtick);
  return values.map((value) => {
    if (!log) return linearLabel(value);
    if (typeof dtick === "string" && dtick[0] === "L") {
      return { value, text: formatNumber(10 ** value, { round, exponent, exponentformat }), scale: 1 };
    }
    const power = typeof dtick === "number" || mod(value + 0.01, 1) < 0.1;
    if (!power) return { value, text: String(Math.round(10 ** mod(value, 1))), scale: 0.75 };
    const p = Math.round(value);
    if (exponentformat === "power") {
      const text = p === 0 ? "1" : p === 1 ? "10" : `10<sup>${p > 1 ? "" : MINUS}${Math.abs(p)}</sup>`;
      return { value, text, scale: 1.25 };
    }
    return { value, text: formatNumber(10 ** value, { round: 0, exponent: 0, exponentformat }), scale: 1 };
  });
}

/** Tick values from the range's start (widened by 1e-4 of it, as Plotly does) to its end. */
function tickValues(range, dtick) {
  const [lo, hi] = range;
  const reach = (hi - lo) * 1e-4;
  const first = lo - reach;
  const last = hi + reach;
  const values = [];
  if (typeof dtick === "number") {
    for (let x = Math.ceil(first / dtick) * dtick; x <= last && values.length < 1000; x += dtick) {
      values.push(x);
    }
  } else if (dtick[0] === "L") {
    const step = Number(dtick.slice(1));
    for (let x = Math.ceil(10 ** first / step) * step; Math.log10(x) <= last; x += step) {
      values.push(Math.log10(x));
    }
  } else {
    // 1, 2, 5 (D2) or 1…9 (D1) times each power of ten
    const set = dtick === "D2" ? LOG_DIGITS_D2 : LOG_DIGITS_D1;
    const digits = dtick === "D2" ? [1, 2, 5, 10] : [1, 2, 3, 4, 5, 6, 7, 8, 9, 10];
    let x = Math.floor(first) + Math.log10(Math.round(10 ** roundUp(mod(first, 1), set) * 10) / 10);
    while (x <= last && values.length < 1000) {
      values.push(x);
      const decade = Math.floor(x + 1e-9);
      const digit = Math.round(10 ** (x - decade));
      x = decade + Math.log10(digits[digits.indexOf(digit) + 1]);
    }
  }
  return values;
}
