"""The explorer as a person meets it, measured in headless Chromium.

    .venv/bin/python benchmarks/bench_page.py [--presses N] [--loads N] [--only keys,load]

1. keys: a key press on each slider (ArrowRight/ArrowLeft on the focused range input, as a
   keyboard user or a person nudging a slider does, 150 ms apart) to the plots updated:
   from the ``keydown`` event to ``#plots`` signalling the new frame drawn (its
   ``data-frame`` changes with ``data-ready="true"``), both read with ``performance.now()``
   in the page. The mass m moves only the simulations, so for m the end is the ramp
   experiment redrawn (``data-ramp-frame``). p50/p95 per slider, the default page (ramp
   and simulation on), 1280×800. Against it, in the same run: the same presses with the
   next arrow step's frame asked for ahead but its plots not drawn ahead into the hidden
   graphs (``window.breakaway.drawAhead(false)``: every press waits for ``Plotly.react``),
   with nothing ahead (``window.breakaway.prefetch(false)``: every press waits for its
   request too), and, without drawing ahead, with every plot that changed drawn from
   scratch (``Plotly.purge`` + ``newPlot``) instead of ``Plotly.react``.
2. load: first load on an emulated 20 Mbit/s link with 40 ms latency (Chrome DevTools
   network emulation, cache disabled), navigation start to four drawn plots: the page as
   served (Plotly's partial bundle, gzip) against the full Plotly bundle (4.8 MB) served
   the same way, and against the full bundle uncompressed (how it was served before). The
   full bundle comes from the ``plotly`` Python package (``pip install -e .[bench]``).

Nothing is asserted; tests check behaviour, this file reports speed.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

from bench_explorer import free_port, load_average, machine, pct

ROOT = Path(__file__).resolve().parents[1]
FRONTEND = ROOT / "frontend"
BROWSER_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                "--disable-component-update", "--disable-sync"]
TARGETS = {"p50_ms": 40, "p95_ms": 80, "m_p50_ms": 150, "load_s": 3.0}
SLIDERS = ["Fc", "Fs", "V", "delta", "sigma", "k", "s", "z_ba", "m"]

#: Installed once per page: the time of every keydown, and of every new frame.
PROBE = """
() => {
  const probe = window.__probe = {key: 0, frame: 0, ramp: 0};
  document.addEventListener('keydown', () => { probe.key = performance.now(); }, true);
  const plots = document.getElementById('plots');
  new MutationObserver((records) => {
    for (const record of records) {
      if (record.attributeName === 'data-frame' && plots.dataset.ready === 'true') {
        probe.frame = performance.now();
      }
      if (record.attributeName === 'data-ramp-frame') probe.ramp = performance.now();
    }
  }).observe(plots, {attributes: true, attributeFilter: ['data-frame', 'data-ramp-frame']});
}
"""

#: The alternative: each redraw from scratch (``Plotly.purge`` + ``newPlot``) instead of
#: ``Plotly.react``'s update of what changed.
NEW_PLOT = """
() => {
  Plotly.react = (gd, data, layout, config) => {
    Plotly.purge(gd);
    return Plotly.newPlot(gd, data, layout, config);
  };
}
"""


class Server:
    """``breakaway serve`` on a free port, optionally with another frontend folder."""

    def __init__(self, frontend: Path | None = None):
        self.port = free_port()
        env = dict(os.environ)
        if frontend is not None:
            env["BREAKAWAY_FRONTEND_DIR"] = str(frontend)
        self.process = subprocess.Popen(
            [sys.executable, "-m", "breakaway", "serve", "--port", str(self.port)],
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 60
        while True:
            try:
                with urllib.request.urlopen(f"{self.url}/api/health", timeout=1):
                    break
            except OSError:
                if time.monotonic() > deadline or self.process.poll() is not None:
                    raise RuntimeError("server did not start")
                time.sleep(0.1)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.process.terminate()
        try:
            self.process.wait(10)
        except subprocess.TimeoutExpired:
            self.process.kill()


def launch(playwright):
    chromium = os.environ.get("BREAKAWAY_CHROMIUM") or (
        "/usr/bin/chromium" if Path("/usr/bin/chromium").exists() else None)
    return playwright.chromium.launch(executable_path=chromium, headless=True,
                                      args=BROWSER_ARGS)


def press_latencies(page, name: str, presses: int) -> list[float]:
    """Key press → plots updated [ms], ``presses`` times on one slider."""
    marker = "ramp" if name == "m" else "frame"
    page.focus(f"#{name}-range")
    # five steps towards the farther end of the slider, five back, and so on
    room = page.evaluate(f"""() => {{ const r = document.getElementById('{name}-range');
        return [r.value - r.min, r.max - r.value]; }}""")
    keys = ("ArrowRight", "ArrowLeft") if room[1] >= room[0] else ("ArrowLeft", "ArrowRight")
    out = []
    for i in range(presses):
        key = keys[(i // 5) % 2]
        page.keyboard.press(key)
        deadline = time.monotonic() + 10
        while True:
            done = page.evaluate(
                f"() => __probe.{marker} > __probe.key ? __probe.{marker} - __probe.key : null")
            if done is not None:
                break
            if time.monotonic() > deadline:
                raise RuntimeError(f"no redraw after a key press on {name}")
            time.sleep(0.005)
        out.append(done)
        # let the debounced ramp and simulation of this press run, as between a
        # person's key presses
        time.sleep(0.15)
        page.evaluate("window.breakaway.rampReady()")
    return out


def bench_keys(presses: int) -> None:
    from playwright.sync_api import sync_playwright

    print(f"\n1. Key press on a slider → plots updated, in the page ({presses} presses per "
          f"slider, 150 ms apart; Chromium headless, 1280×800; load average {load_average()})")
    print(f"   targets: p50 ≤ {TARGETS['p50_ms']} ms, p95 ≤ {TARGETS['p95_ms']} ms; "
          f"m (the simulations) p50 ≤ {TARGETS['m_p50_ms']} ms")
    with Server() as server, sync_playwright() as playwright:
        browser = launch(playwright)
        results = {}
        hits = surfaces = None
        variants = (("the page", []),
                    ("not drawn ahead", ["window.breakaway.drawAhead(false)"]),
                    ("nothing ahead", ["window.breakaway.prefetch(false)"]),
                    ("newPlot", ["window.breakaway.drawAhead(false)", NEW_PLOT]))
        for label, setup in variants:
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            page.goto(f"{server.url}/")
            page.evaluate("window.breakaway.rampReady()")
            page.evaluate(PROBE)
            for script in setup:
                page.evaluate(script)
            results[label] = {name: press_latencies(page, name, presses) for name in SLIDERS}
            if label == "the page":
                hits = page.evaluate("window.breakaway.prefetchHits()")
                surfaces = page.evaluate("window.breakaway.surfaces()")
            page.close()
        browser.close()
    labels = list(results)
    print(f"   {'slider':8s}" + "".join(f" {label + ': p50':>22s} {'p95':>8s}" for label in labels))
    for name in SLIDERS:
        print(f"   {name:8s}" + "".join(
            f" {pct(results[label][name], .5):19.1f} ms {pct(results[label][name], .95):5.1f} ms"
            for label in labels))
    for label in labels:
        every = [v for name in SLIDERS if name != "m" for v in results[label][name]]
        print(f"   all sliders but m, {label}: p50 {pct(every, .5):.1f} ms, "
              f"p95 {pct(every, .95):.1f} ms")
    print(f"   presses that found their frame asked for ahead: {hits} of "
          f"{presses * (len(SLIDERS) - 1)} (m asks for no frame)")
    print(f"   the page's plots: {surfaces['swaps']} shown from the graph drawn ahead, "
          f"{surfaces['reacts']} drawn by Plotly.react when shown (the ramp's simulated "
          f"path, turns of direction), {surfaces['drawnAhead']} drawn ahead")


def first_load(browser, url: str, identity: bool) -> float:
    """Navigation start to four drawn plots [s] on an emulated 20 Mbit/s, 40 ms link."""
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    page = context.new_page()
    cdp = context.new_cdp_session(page)
    cdp.send("Network.enable")
    cdp.send("Network.setCacheDisabled", {"cacheDisabled": True})
    cdp.send("Network.emulateNetworkConditions", {
        "offline": False, "latency": 40,
        "downloadThroughput": 20e6 / 8, "uploadThroughput": 20e6 / 8})
    if identity:
        cdp.send("Network.setExtraHTTPHeaders", {"headers": {"Accept-Encoding": "identity"}})
    page.goto(url, wait_until="commit")
    page.wait_for_function("() => window.breakaway !== undefined", timeout=60_000)
    page.evaluate("window.breakaway.ready()")
    seconds = page.evaluate("performance.now()") / 1000
    context.close()
    return seconds


def bench_load(loads: int) -> None:
    from playwright.sync_api import sync_playwright

    print(f"\n2. First load, 20 Mbit/s and 40 ms emulated, cache off: navigation start to four "
          f"drawn plots ({loads} loads each; target ≤ {TARGETS['load_s']} s)")
    try:
        import plotly
        full = Path(plotly.__file__).resolve().parent / "package_data" / "plotly.min.js"
    except ImportError:
        full = None
    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as playwright:
        browser = launch(playwright)
        variants = [("partial bundle (1.2 MB), gzip — the page", None, False)]
        if full is not None:
            swapped = Path(tmp) / "frontend"
            shutil.copytree(FRONTEND, swapped)
            shutil.copyfile(full, swapped / "vendor" / "plotly-basic-4.1.1.min.js")
            size = full.stat().st_size / 1e6
            variants += [(f"full bundle ({size:.1f} MB), gzip", swapped, False),
                         (f"full bundle ({size:.1f} MB), uncompressed", swapped, True)]
        else:
            print("   (the plotly package is not installed: no full-bundle comparison)")
        for label, frontend, identity in variants:
            with Server(frontend) as server:
                times = [first_load(browser, f"{server.url}/", identity) for _ in range(loads)]
            print(f"   {label:42s} median {statistics.median(times):.2f} s "
                  f"(min {min(times):.2f}, max {max(times):.2f})")
        browser.close()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--presses", type=int, default=40)
    parser.add_argument("--loads", type=int, default=3)
    parser.add_argument("--only", default="keys,load")
    args = parser.parse_args(argv)
    print(f"Machine: {machine()}")
    sections = args.only.split(",")
    if "keys" in sections:
        bench_keys(args.presses)
    if "load" in sections:
        bench_load(args.loads)
    return 0


if __name__ == "__main__":
    sys.exit(main())
