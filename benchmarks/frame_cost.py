"""What a live frame costs the page's main thread, in CPU time, by phase.

    .venv/bin/python benchmarks/frame_cost.py [--ab REF] [--sliders Fs,k] [--rounds N]

benchmarks/ui_latency.py measures time on the clock, which on this shared two-core
machine moves with the load beside it (another process's two busy cores halve a frame's
pace), and its 4× CPU slow-down makes the page's main thread spin while it is held, so
that its CPU time is the clock's too. This file takes a Chromium trace of the same
inputs at the machine's speed (ui_latency's harness: a drag of 2 s, 20 key presses 150
ms apart, the plots in view) and sums the main thread's CPU time (the trace's thread
clock), which the load moves far less: per frame of a drag, the whole main thread and
its phases (the page's script at the animation frame, the input handlers and timers,
style and layout, pre-paint, paint, the commit); per key press, the handler and the
animation frame the press waits for (the latency less the wait for that frame). Four
times these is what the throttled run's main thread is given to do.

`--ab REF`: the frontend of git revision REF (A) against the working tree's (B), taking
turns as in ui_latency.py; medians and spread over `--rounds`. Nothing is asserted and
nothing is written to the docs.
"""

from __future__ import annotations

import argparse
import collections
import json
import statistics
import sys
import tempfile
from pathlib import Path

from bench_page import Server, launch
from results import load_average, machine
from ui_latency import HARNESS, frontend_at, open_page, pct

CATEGORIES = ["devtools.timeline", "disabled-by-default-devtools.timeline", "blink", "cc", "toplevel"]
#: Trace events of the main thread by phase; nested ones are counted in their own phase
#: only (the animation frame's script is inside BeginMainFrame, which is not a phase).
PHASES = {
    "script (animation frame)": ["FireAnimationFrame"],
    "input handlers and timers": ["EventDispatch", "TimerFire"],
    "style and layout": ["UpdateLayoutTree", "Layout"],
    "pre-paint": ["PrePaint"],
    "paint": ["LocalFrameView::RunPaintLifecyclePhase"],
    "commit": ["Commit"],
}


def main_thread(events: list[dict]) -> list[dict]:
    """The complete events of the page's renderer main thread, by start time."""
    names = {(e["pid"], e["tid"]): e["args"]["name"] for e in events
             if e.get("ph") == "M" and e.get("name") == "thread_name"}
    counts = collections.Counter((e["pid"], e["tid"]) for e in events
                                 if names.get((e["pid"], e["tid"])) == "CrRendererMain")
    thread = counts.most_common(1)[0][0]
    return sorted((e for e in events if (e["pid"], e["tid"]) == thread and e.get("ph") == "X"
                   and "tdur" in e), key=lambda e: e["ts"])


def inputs_of(events: list[dict], kind: str) -> list[dict]:
    return [e for e in events if e["name"] == "EventDispatch"
            and e.get("args", {}).get("data", {}).get("type") == kind]


def drag_cost(events: list[dict]) -> dict:
    """CPU per frame [ms] over the drag, in all and by phase."""
    inputs = inputs_of(events, "input")
    start, end = inputs[0]["ts"], inputs[-1]["ts"]
    inside = [e for e in events if start <= e["ts"] <= end]
    frames = sum(e["name"] == "ProxyMain::BeginMainFrame" for e in inside) or 1
    cost = {"main thread": sum(e["tdur"] for e in inside if e["name"] == "ThreadControllerImpl::RunTask")}
    for phase, names in PHASES.items():
        cost[phase] = sum(e["tdur"] for e in inside if e["name"] in names)
    # the harness dispatches a drag's inputs from an animation frame callback, as Chromium
    # does a pointer's: their handlers are counted as handlers, not as the frame's script
    callbacks = [e for e in inside if e["name"] == "FireAnimationFrame"]
    cost["script (animation frame)"] -= sum(
        e["tdur"] for e in inside if e["name"] == "EventDispatch"
        and any(f["ts"] <= e["ts"] <= f["ts"] + f["dur"] for f in callbacks))
    return {phase: value / 1000 / frames for phase, value in cost.items()}


def key_costs(events: list[dict]) -> list[float]:
    """CPU of each press's handler and of the animation frame after it [ms]."""
    frames = [e for e in events if e["name"] == "FireAnimationFrame"]
    out = []
    for press in inputs_of(events, "keydown"):
        frame = next((e for e in frames if e["ts"] > press["ts"]), None)
        if frame is not None:
            out.append((press["tdur"] + frame["tdur"]) / 1000)
    return out


def measure(browser, url: str, slider: str) -> dict:
    """A traced drag and 20 traced key presses of `slider` on a fresh page."""
    out = {}
    for mode in ("drag", "keys"):
        page = open_page(browser, url, [], 1)
        browser.start_tracing(page=page, categories=CATEGORIES)
        page.evaluate(HARNESS, {"name": slider, "mode": mode, "presses": 20, "gaps": [150],
                                "seconds": 2, "hz": 60})
        events = main_thread(json.loads(browser.stop_tracing())["traceEvents"])
        out[mode] = drag_cost(events) if mode == "drag" else key_costs(events)
        page.close()
    return out


def spread(values) -> str:
    return f"{statistics.median(values):5.2f} [{min(values):.2f}–{max(values):.2f}]"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ab", metavar="REF",
                        help="the frontend of git revision REF against the working tree's")
    parser.add_argument("--sliders", default="Fs,k")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args(argv)
    sliders = args.sliders.split(",")
    print(f"Machine: {machine()}; load average at the start {load_average()}")
    from playwright.sync_api import sync_playwright

    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as playwright:
        frontends = {"this frontend": None}
        if args.ab:
            frontends = {f"A {args.ab}": frontend_at(args.ab, Path(tmp)), "B working tree": None}
        servers = {label: Server(frontend) for label, frontend in frontends.items()}
        try:
            browser = launch(playwright)
            runs = {(label, name): [] for label in servers for name in sliders}
            for round_ in range(args.rounds):
                for i, name in enumerate(sliders):
                    labels = list(servers) if (i + round_) % 2 == 0 else list(servers)[::-1]
                    for label in labels:
                        runs[label, name].append(measure(browser, servers[label].url, name))
                print(f"round {round_ + 1} done (load average {load_average()})")
            browser.close()
        finally:
            for server in servers.values():
                server.__exit__(None, None, None)
    print(f"\nMain thread CPU [ms], median [min–max] over {args.rounds} rounds, at the machine's speed:")
    for (label, name), rounds in runs.items():
        print(f"  {name} {label}:")
        print(f"    a frame of a drag: " + ", ".join(
            f"{phase} {spread([r['drag'][phase] for r in rounds])}" for phase in rounds[0]["drag"]))
        print(f"    a key press (handler + its frame): p50 {spread([pct(r['keys'], .5) for r in rounds])}, "
              f"p95 {spread([pct(r['keys'], .95) for r in rounds])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
