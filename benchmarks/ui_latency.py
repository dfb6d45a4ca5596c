"""The explorer at the speed of a hand: input to plots showing the new value, in the page.

    .venv/bin/python benchmarks/ui_latency.py [--presses N] [--sliders Fc,Fs,...] [--only keys,slow,drag]
                                              [--throttle 1,4] [--ab REF [--rounds N]]

Headless Chromium, 1280×800, the default page (the ramp and the simulation on). Events
come from timers in the page, so their spacing is the page's, not Playwright's. Every
figure is measured twice: at the machine's speed, and with Chromium's CPU throttled 4×
(`--throttle`; DevTools' Emulation.setCPUThrottlingRate, as page-speed tools emulate a
mid-range phone), the throttled run beside the plain one.

- keys: keydown events on the focused slider, 150 ms apart, five presses one way and
  five back (so half the presses go each way, and every fifth turns); `--presses` per
  slider. Figures for presses to the right, to the left, and for the turns.
- slow keys: the same, at a person's uneven pace: 200–700 ms apart (seeded uniform), so
  that the settled Plotly drawing runs between presses and a press may land on it.
- drag: a pointer dragging the slider for 2 s over 60–100 positions and back (a
  triangle on the clock, position i of 120 at i/60 s), then `change` (the release). Its
  inputs come as Chromium delivers a moving pointer's: one a frame, the latest position
  (the events since the frame before coalesced), none when the slider did not move, at
  the start of the frame, before its animation frame callbacks, so what the handler
  asks for draws in that frame. A script cannot dispatch there (a callback asked for
  during a frame's callbacks runs at the next frame), so the harness dispatches from a
  callback that runs after the page's own, each frame, the position reached by then:
  the page draws it at the next frame, where Chromium would have dispatched it. The
  page's work a frame is the same (one input's handler, one frame); latency counts from
  the dispatch, so it holds the wait for the frame that a pointer's event has. A page
  that falls behind gets the position the hand has reached when it takes one. (Each
  input from its own timer waited behind the frame then running and 4 ms more: a page
  framing every 16.7 ms at 4× got an input every 35 ms, and frames per second measured
  that pace; all overdue inputs in one timer task gave two handlers a frame.)

The plots a slider's frames count are scrolled into view first, as a person watches
them (a plot out of view is drawn live only when it comes into view). A frame counts
when `#plots` `data-frame` changes (for m: `data-ramp-frame`, the ramp experiment being
the only plot m moves; for a slider named `loop:<name>`, e.g. `--sliders
loop:Ki,loop:Fs`: `data-loop-frame`, the control loop's plots) and what it shows is the
state with the new value; latency is from the event to that frame, both read with
`performance.now()`. A drag's latency is from each input to the first frame showing it
or a later input; frames per second count the frames shown during the drag; "last" is
from the last input to the frame showing its value. The obvious alternative runs in the
same session: every input drawn by `Plotly.react` as it comes
(`window.breakaway.live(false)`: no live canvas, no waiting for the hand to rest).

A/B (`--ab REF`): the frontend of git revision REF (A) against the working tree's (B),
each served by its own server, in the same run; no Plotly.react column. On this shared
two-core machine the load beside a run moves its figures as much as a change of a few
milliseconds does, so runs one after the other cannot show such a change: here both
pages stay open and take turns slider by slider (A then B, then B then A), so the load
falls on both alike, for `--rounds` rounds. The report gives each round's figures and
their median and spread; nothing is written to the docs.

Goal (issue 21): p50 ≤ 16 ms and p95 ≤ 33 ms for every slider, either way, keys or
pointer; during a drag ≥ 30 frames per second and the last value shown ≤ 50 ms after the
last input. Goal (issue 27), the CPU throttled 4×: key presses p50 ≤ 16 ms and p95 ≤ 33 ms,
drags ≥ 30 frames per second. Nothing is asserted; tests check behaviour, this file
reports speed.
"""

from __future__ import annotations

import argparse
import random
import statistics
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

from bench_explorer import load_average, machine, pct
from bench_page import Server, launch
from results import Results

SLIDERS = ["Fc", "Fs", "V", "delta", "sigma", "k", "s", "z_ba", "m"]

#: Installed for one run on one slider: records each frame shown (time, value shown).
HARNESS = """
async ({name: slider, mode, presses, gaps, seconds, hz}) => {
  const plots = document.getElementById('plots');
  const loop = slider.startsWith('loop:');
  const name = loop ? slider.slice(5) : slider;
  const range = document.getElementById(name + '-range');
  const ramp = name === 'm' && !loop;
  const attr = loop ? 'data-loop-frame' : ramp ? 'data-ramp-frame' : 'data-frame';
  // the loop's answer gives its mass as the plant's m
  const shownValue = () => (loop ? window.breakaway.loopParams()?.[name === 'm_loop' ? 'm' : name]
    : ramp ? window.breakaway.viewParams('ramp')?.m : window.breakaway.state()[name]);
  const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
  // the plots this slider's frames count in view, as a person watches them (a plot out
  // of view is drawn when it comes into view); the loop follows a friction slider live
  // while its card is on the screen
  document.getElementById(loop ? 'card-loop' : ramp ? 'plot-ramp' : 'plot-stribeck').scrollIntoView();
  await sleep(100);
  const shown = [];
  let last = plots.getAttribute(attr);
  const observer = new MutationObserver(() => {
    const value = plots.getAttribute(attr);
    if (value !== last) { last = value; shown.push([performance.now(), shownValue()]); }
  });
  observer.observe(plots, {attributes: true, attributeFilter: [attr]});
  range.focus();
  const inputs = [];
  if (mode === 'keys') {
    // five steps towards the farther end, five back, …
    const room = [range.value - range.min, range.max - range.value];
    const keys = room[1] >= room[0] ? ['ArrowRight', 'ArrowLeft'] : ['ArrowLeft', 'ArrowRight'];
    for (let i = 0; i < presses; i++) {
      await sleep(gaps[i % gaps.length]);
      const key = keys[Math.floor(i / 5) % 2];
      const event = new KeyboardEvent('keydown', {key, bubbles: true, cancelable: true});
      const t = performance.now();
      range.dispatchEvent(event);
      inputs.push({t, value: window.breakaway.state()[name], key, turn: i > 0 && i % 5 === 0});
    }
  } else {
    const count = Math.round(seconds * hz);
    const start = Number(range.value);
    // at least a position a tick (count / 2 each way): the pointer moves it every frame
    const span = Math.min(100, Math.max(count / 2, Math.floor((range.max - range.min) / 4)));
    const reach = start + span <= Number(range.max) ? span : -span;
    // the pointer's i-th position (of `count`, at `hz`): there and back, a triangle
    const position = (i) => {
      const phase = i / count;
      const offset = Math.round(reach * (phase < 0.5 ? 2 * phase : 2 - 2 * phase));
      return String(start + (offset === 0 && i < count ? Math.sign(reach) : offset));
    };
    range.dispatchEvent(new PointerEvent('pointerdown', {bubbles: true}));
    const begin = performance.now();
    // once a frame, after the page's own callbacks of that frame (this one asks for the
    // next frame after its input made the page ask), the latest position the pointer has
    // reached, if it moved the slider: the page draws it at the next frame
    let moved = null;
    await new Promise((resolve) => {
      const dispatch = () => {
        const reached = Math.min(count, Math.floor(((performance.now() - begin) * hz) / 1000));
        const value = position(Math.max(1, reached));
        if (value !== moved) {
          moved = value;
          range.value = value;
          const t = performance.now();
          range.dispatchEvent(new Event('input', {bubbles: true}));
          inputs.push({t, value: window.breakaway.state()[name]});
        }
        if (reached < count) requestAnimationFrame(dispatch);
        else resolve();
      };
      requestAnimationFrame(dispatch);
    });
    range.dispatchEvent(new Event('change', {bubbles: true}));
    range.dispatchEvent(new PointerEvent('pointerup', {bubbles: true}));
  }
  await window.breakaway.ready();
  await window.breakaway.rampReady();
  if (loop) await window.breakaway.loopReady();
  await sleep(100);
  observer.disconnect();
  return {inputs, shown};
}
"""


def key_latencies(run: dict) -> list[tuple[dict, float]]:
    """Each press and the time to the first frame showing its value [ms]."""
    out = []
    for press in run["inputs"]:
        frame = next((t for t, value in run["shown"] if t >= press["t"] and value == press["value"]), None)
        if frame is not None:
            out.append((press, frame - press["t"]))
    return out


def drag_figures(run: dict) -> dict:
    """Latency per input (to a frame showing it or a later input), frames per second
    during the drag, and the last input to the frame showing it [ms]."""
    inputs = run["inputs"]
    latencies = []
    for i, event in enumerate(inputs):
        later = {e["value"] for e in inputs[i:]}
        frame = next((t for t, value in run["shown"] if t >= event["t"] and value in later), None)
        if frame is not None:
            latencies.append(frame - event["t"])
    start, end = inputs[0]["t"], inputs[-1]["t"]
    during = [t for t, _ in run["shown"] if start <= t <= end]
    final = next((t for t, value in run["shown"] if t >= end and value == inputs[-1]["value"]), None)
    return {"latencies": latencies, "fps": len(during) / ((end - start) / 1000),
            "last": None if final is None else final - end}


def run_variant(page, sliders, mode, args) -> dict:
    out = {}
    pace = random.Random(21)
    for name in sliders:
        gaps = [pace.uniform(200, 700) for _ in range(args.presses)] if mode == "slow" else [150]
        out[name] = page.evaluate(HARNESS, {
            "name": name, "mode": "keys" if mode in ("keys", "slow") else "drag",
            "presses": args.presses, "gaps": gaps, "seconds": 2, "hz": 60})
    return out


def open_page(browser, url, setup, rate):
    """The default page at 1280×800, ready, `setup` run in it, its CPU slowed `rate`×."""
    page = browser.new_page(viewport={"width": 1280, "height": 800})
    page.set_default_timeout(600_000)
    page.goto(f"{url}/")
    page.evaluate("window.breakaway.rampReady()")
    page.evaluate("window.breakaway.simReady()")
    for script in setup:
        page.evaluate(script)
    if rate != 1:
        cdp = page.context.new_cdp_session(page)
        cdp.send("Emulation.setCPUThrottlingRate", {"rate": rate})
    return page


def fmt(values, q) -> str:
    return f"{pct(values, q):6.1f}" if values else "     –"


def report_keys(results: dict, sliders: list[str], rows, title) -> None:
    labels = list(results)
    print(f"   {'slider':7s}" + "".join(
        f" | {label:>34s}: right p50/p95, left p50/p95, turns p50" for label in labels))
    totals = {label: [] for label in labels}
    for name in sliders:
        row = f"   {name:7s}"
        for label in labels:
            pairs = key_latencies(results[label][name])
            totals[label] += [ms for _, ms in pairs]
            right = [ms for press, ms in pairs if press["key"] == "ArrowRight"]
            left = [ms for press, ms in pairs if press["key"] == "ArrowLeft"]
            turns = [ms for press, ms in pairs if press["turn"]]
            row += (f" | {fmt(right, .5)} {fmt(right, .95)}  {fmt(left, .5)} {fmt(left, .95)} "
                    f" {fmt(turns, .5)}  ({len(pairs)}/{len(results[label][name]['inputs'])} shown)")
        print(row)
    for label in labels:
        every = totals[label]
        print(f"   every slider, {label}: p50 {pct(every, .5):.1f} ms, p95 {pct(every, .95):.1f} ms, "
              f"max {max(every):.1f} ms ({len(every)} presses)")
    rows.append([f"{title}, every slider: p50 / p95 / max"] + [
        f"{pct(totals[label], .5):.1f} / {pct(totals[label], .95):.1f} / "
        f"{max(totals[label]):.1f} ms" for label in labels])


def report_drags(results: dict, sliders: list[str], rows) -> None:
    labels = list(results)
    print(f"   {'slider':7s}" + "".join(
        f" | {label:>34s}: frames/s, p50, p95, last [ms]" for label in labels))
    for name in sliders:
        row = f"   {name:7s}"
        for label in labels:
            figures = drag_figures(results[label][name])
            last = "   –" if figures["last"] is None else f"{figures['last']:5.1f}"
            row += (f" | {figures['fps']:6.1f} {fmt(figures['latencies'], .5)} "
                    f"{fmt(figures['latencies'], .95)} {last}")
        print(row)
        cells = []
        for label in labels:
            figures = drag_figures(results[label][name])
            last = "–" if figures["last"] is None else f"{figures['last']:.1f}"
            cells.append(f"{figures['fps']:.1f}/s, {pct(figures['latencies'], .5):.1f}, "
                         f"{pct(figures['latencies'], .95):.1f}, {last} ms")
        rows.append([f"drag of {name}: frames per second, p50, p95, last value after the "
                     f"last input"] + cells)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--presses", type=int, default=40)
    parser.add_argument("--sliders", default=",".join(SLIDERS))
    parser.add_argument("--only", default="keys,slow,drag")
    parser.add_argument("--throttle", default="1,4",
                        help="CPU slow-down factors to run at (1: the machine's speed)")
    parser.add_argument("--ab", metavar="REF",
                        help="A/B: the frontend of git revision REF against the working tree's")
    parser.add_argument("--rounds", type=int, default=3, help="A/B: rounds of alternated runs")
    args = parser.parse_args(argv)
    sliders = args.sliders.split(",")
    rates = [float(rate) for rate in args.throttle.split(",")]
    print(f"Machine: {machine()}; load average at the start {load_average()}")
    if args.ab:
        return ab_main(args, sliders, rates)
    from playwright.sync_api import sync_playwright

    variants = (("the page (live frames)", []),
                ("Plotly.react per input", ["window.breakaway.live(false)"]))
    out, rows = Results("ui_latency", __file__), []
    with Server() as server, sync_playwright() as playwright:
        browser = launch(playwright)
        for mode in args.only.split(","):
            results = {}
            for rate in rates:
                for label, setup in variants:
                    page = open_page(browser, server.url, setup, rate)
                    results[label if rate == 1 else f"{label}, CPU {rate:g}× slower"] = \
                        run_variant(page, sliders, mode, args)
                    page.close()
            title = {"keys": "Key presses 150 ms apart", "slow": "Key presses 200–700 ms apart (settles in between)",
                     "drag": "Pointer drags: 2 s, an input a frame (the latest position), then the release"}[mode]
            print(f"\n{title} (load average {load_average()}), event → frame showing the value [ms]:")
            if mode == "drag":
                report_drags(results, sliders, rows)
            else:
                report_keys(results, sliders, rows, title)
        browser.close()
    print()
    # a column per variant and CPU rate, in the order the rows' cells are
    out.table(["", *(label if rate == 1 else f"{label}, CPU {rate:g}× slower"
                     for rate in rates for label, _ in variants)], rows)
    out.note(f"Sliders: {', '.join(sliders)}; {args.presses} presses each; headless Chromium "
             f"at 1280×800; latency from the event to the frame that shows the value.")
    out.write()
    return 0


def frontend_at(ref: str, into: Path) -> Path:
    """The frontend folder of git revision `ref`, written under `into`."""
    root = Path(__file__).resolve().parents[1]
    archive = subprocess.run(["git", "archive", ref, "frontend"], cwd=root, check=True,
                             capture_output=True).stdout
    with tempfile.TemporaryFile() as fh:
        fh.write(archive)
        fh.seek(0)
        with tarfile.open(fileobj=fh) as tar:
            tar.extractall(into, filter="data")
    return into / "frontend"


def spread(values, unit="") -> str:
    """Median [min–max] of one figure over rounds."""
    return (f"{statistics.median(values):.1f} [{min(values):.1f}–{max(values):.1f}]{unit}"
            if values else "–")


def ab_main(args, sliders, rates) -> int:
    """Revision `args.ab`'s frontend (A) against the working tree's (B), alternated."""
    from playwright.sync_api import sync_playwright

    labels = (f"A {args.ab}", "B working tree")
    modes = args.only.split(",")
    # figures[mode][label, rate] -> one dict per round
    figures = {mode: {(label, rate): [] for label in labels for rate in rates} for mode in modes}
    with tempfile.TemporaryDirectory() as tmp, Server(frontend_at(args.ab, Path(tmp))) as a_server, \
            Server() as b_server, sync_playwright() as playwright:
        browser = launch(playwright)
        urls = dict(zip(labels, (a_server.url, b_server.url)))
        for round_ in range(args.rounds):
            for mode in modes:
                for rate in rates:
                    pages = {label: open_page(browser, urls[label], [], rate) for label in labels}
                    runs = {label: {} for label in labels}
                    for i, name in enumerate(sliders):
                        # A then B, then B then A: neither always runs first
                        for label in (labels if (i + round_) % 2 == 0 else labels[::-1]):
                            pages[label].bring_to_front()
                            runs[label] |= run_variant(pages[label], [name], mode, args)
                    for label in labels:
                        pages[label].close()
                        figures[mode][label, rate].append(round_figures(runs[label], mode))
                print(f"round {round_ + 1}, {mode} (load average {load_average()}):")
                for (label, rate), rounds in figures[mode].items():
                    print(f"   {label:>24s} CPU {rate:g}×: {describe(rounds[-1], mode)}")
        browser.close()
    print(f"\nMedian [min–max] over {args.rounds} rounds (load average at the end {load_average()}):")
    for mode in modes:
        for (label, rate), rounds in figures[mode].items():
            if mode == "drag":
                line = (f"frames/s: median of sliders {spread([r['fps'] for r in rounds])}, "
                        f"slowest slider {spread([r['fps_min'] for r in rounds])}; "
                        f"p50 {spread([r['p50'] for r in rounds], ' ms')}")
            else:
                line = (f"p50 {spread([r['p50'] for r in rounds], ' ms')}, "
                        f"p95 {spread([r['p95'] for r in rounds], ' ms')}")
            print(f"   {mode:5s} {label:>24s} CPU {rate:g}×: {line}")
    return 0


def round_figures(run: dict, mode: str) -> dict:
    """One round's figures of one variant: every slider's presses or drags pooled."""
    if mode == "drag":
        drags = [drag_figures(one) for one in run.values()]
        every = [ms for figures in drags for ms in figures["latencies"]]
        fps = [figures["fps"] for figures in drags]
        return {"fps": statistics.median(fps), "fps_min": min(fps), "p50": pct(every, .5),
                "per_slider": dict(zip(run, fps))}
    every = [ms for one in run.values() for _, ms in key_latencies(one)]
    return {"p50": pct(every, .5), "p95": pct(every, .95), "count": len(every)}


def describe(figures: dict, mode: str) -> str:
    if mode == "drag":
        return (f"frames/s median {figures['fps']:.1f}, slowest {figures['fps_min']:.1f} ("
                + ", ".join(f"{name} {fps:.0f}" for name, fps in figures["per_slider"].items())
                + f"); p50 {figures['p50']:.1f} ms")
    return f"p50 {figures['p50']:.1f} ms, p95 {figures['p95']:.1f} ms ({figures['count']} presses)"


if __name__ == "__main__":
    sys.exit(main())
