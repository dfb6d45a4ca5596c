"""The explorer's first load, measured in headless Chromium.

    .venv/bin/python benchmarks/bench_page.py [--loads N]

First load on an emulated 20 Mbit/s link with 40 ms latency (Chrome DevTools network
emulation, cache disabled), navigation start to four drawn plots: the page as served
(Plotly's partial bundle, gzip) against the full Plotly bundle (4.8 MB) served the same
way, and against the full bundle uncompressed (how it was served before). The full bundle
comes from the ``plotly`` Python package (``pip install -e .[bench]``). Key presses and
drags: benchmarks/ui_latency.py (which uses this file's Server and launch).

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

from bench_explorer import free_port, machine
from results import Results

ROOT = Path(__file__).resolve().parents[1]
FRONTEND = ROOT / "frontend"
BROWSER_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                "--disable-component-update", "--disable-sync"]
TARGETS = {"load_s": 3.0}

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


def bench_load(loads: int, rows) -> None:
    from playwright.sync_api import sync_playwright

    print(f"\nFirst load, 20 Mbit/s and 40 ms emulated, cache off: navigation start to four "
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
            rows.append([label, f"{statistics.median(times):.2f} s",
                         f"{min(times):.2f} … {max(times):.2f} s"])
        browser.close()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--loads", type=int, default=3)
    args = parser.parse_args(argv)
    print(f"Machine: {machine()}")
    out, rows = Results("page", __file__), []
    bench_load(args.loads, rows)
    print()
    out.table(["Plotly bundle", f"first load, median of {args.loads}", "range"], rows)
    out.note(f"Navigation start to four drawn plots on an emulated 20 Mbit/s link with 40 ms "
             f"latency, cache off (Chromium's network emulation); target ≤ "
             f"{TARGETS['load_s']} s.")
    out.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
