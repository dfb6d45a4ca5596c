"""Speed figures of the explorer, each against the obvious alternative.

    .venv/bin/python benchmarks/bench_explorer.py [--quick] [--only serial,server,http,load,browser]

1. serial: one frame to JSON bytes: the compact orjson form the API sends (float32)
   against orjson at full precision, ``json.dumps`` of lists, and the pydantic response
   model (validate + dump), the way FastAPI would with ``response_model``.
2. server: server-side time of ``POST /api/explore`` in process: the whole ASGI app
   (middleware, routing, validation, model, serialisation), bodies varied like slider
   moves, against an empty endpoint through the same stack.
3. http: latency over loopback to the real server (uvicorn, as ``breakaway serve`` runs
   it), sequential keep-alive requests: explore against the empty endpoint (the floor)
   and ``/api/health``; the same with uvicorn's pure-Python h11 + asyncio. Payload sizes.
4. load: ``benchmarks/loadgen.py`` in a second process on 127.0.0.1, 32 connections,
   bounded in count and time: explore (varied bodies) against the empty endpoint.
5. browser: headless Chromium (same flags as the tests) on the explorer: slider input to
   all four plots redrawn (``window.breakaway.ready()``), p50/p95, split into the
   request and the drawing; against redrawing with ``Plotly.purge`` + ``newPlot``.
   The ramp simulation is off here (it runs debounced, apart from the sliders).

Nothing is asserted; the tests check values, this file reports speed. The machine is
shared: the load average is printed with the figures. The table goes to
docs/benchmarks/results/explorer.md, which the documentation includes.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import random
import socket
import statistics
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from results import Results, load_average, machine  # noqa: E402
EXPLORE_TARGET = {"server_p50_ms": 5.0, "floor_ratio": 2.0, "payload_kb": 150,
                  "rate": 300, "browser_p50_ms": 50, "browser_p95_ms": 100}


# ---------------------------------------------------------------------------------
# helpers
# ---------------------------------------------------------------------------------

def pct(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))]


def slider_bodies(n: int, seed: int = 7) -> list[dict]:
    """Request bodies as a person dragging sliders produces them (one parameter moved)."""
    from breakaway.params import DEFAULTS

    rng = random.Random(seed)
    moves = {
        "Fc": lambda: round(rng.uniform(0.4, 1.0), 4),
        "Fs": lambda: round(rng.uniform(1.0, 2.5), 4),
        "V": lambda: round(10 ** rng.uniform(0.8, 2.4), 4),
        "delta": lambda: round(rng.uniform(0.5, 3.0), 2),
        "sigma": lambda: round(10 ** rng.uniform(-4, -1), 6),
        "k": lambda: round(10 ** rng.uniform(-2, 1.47), 4),
        "s": lambda: round(10 ** rng.uniform(-0.4, 1.2), 4),
        "z_ba": lambda: round(rng.uniform(0.5, 0.97), 2),
    }
    bodies = []
    for i in range(n):
        name = list(moves)[i % len(moves)]
        body = {key: value for key, value in DEFAULTS.items()}
        body[name] = moves[name]()
        bodies.append(body)
    return bodies


def bench_app():
    """The production app plus an empty endpoint (the floor) in front of the frontend."""
    from fastapi import Response
    from fastapi.routing import APIRoute

    from breakaway.api.app import create_app

    app = create_app()

    async def empty() -> Response:
        return Response(b"{}", media_type="application/json")

    app.router.routes.insert(0, APIRoute("/bench/empty", empty, methods=["POST"]))
    return app


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


class Server:
    """This file with ``--serve``: uvicorn on ``bench_app``, as ``breakaway serve`` runs."""

    def __init__(self, pure_python: bool = False):
        self.port = free_port()
        command = [sys.executable, str(Path(__file__).resolve()), "--serve", str(self.port)]
        if pure_python:
            command.append("--pure-python")
        self.process = subprocess.Popen(command, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 60
        while True:
            try:
                with urllib.request.urlopen(f"{self.url}/api/health", timeout=1):
                    break
            except OSError:
                if time.monotonic() > deadline or self.process.poll() is not None:
                    raise RuntimeError("benchmark server did not start")
                time.sleep(0.1)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def close(self):
        self.process.terminate()
        try:
            self.process.wait(10)
        except subprocess.TimeoutExpired:
            self.process.kill()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def serve(port: int, pure_python: bool) -> None:
    import uvicorn

    options = {"http": "h11", "loop": "asyncio"} if pure_python else {}
    uvicorn.run(bench_app(), host="127.0.0.1", port=port, log_level="warning", **options)


# ---------------------------------------------------------------------------------
# 1. serialisation
# ---------------------------------------------------------------------------------

def bench_serial(rows, repeat: int) -> None:
    import orjson

    from breakaway.api.encoding import dumps_frame
    from breakaway.api.schemas import ExploreResponse
    from breakaway.frame import explore_frame

    frame = explore_frame()

    def tolists(obj):
        if isinstance(obj, dict):
            return {k: tolists(v) for k, v in obj.items()}
        if isinstance(obj, list):
            return [tolists(v) for v in obj]
        if isinstance(obj, np.ndarray):
            return obj.tolist()
        return obj

    candidates = {
        "compact orjson (API)": lambda: dumps_frame(frame),
        "orjson, full precision": lambda: orjson.dumps(frame, option=orjson.OPT_SERIALIZE_NUMPY),
        "json.dumps of lists": lambda: json.dumps(tolists(frame)).encode(),
        "pydantic response model": lambda: ExploreResponse.model_validate(
            tolists(frame)).model_dump_json(by_alias=True).encode(),
    }
    medians = {}
    print("\n1. One frame to JSON (in process)")
    print(f"   {'method':28s} {'median':>9s} {'size':>9s}")
    for name, func in candidates.items():
        func()
        times = []
        for _ in range(repeat):
            t0 = time.perf_counter()
            size = len(func())
            times.append(time.perf_counter() - t0)
        print(f"   {name:28s} {1e3 * statistics.median(times):7.3f} ms {size / 1024:7.1f} KB")
        medians[name] = 1e3 * statistics.median(times)
    rows.append(["one frame to JSON: compact orjson / `json.dumps` of lists / pydantic model",
                 " / ".join(f"{medians[name]:.2f}" for name in (
                     "compact orjson (API)", "json.dumps of lists", "pydantic response model"))
                 + " ms", ""])


# ---------------------------------------------------------------------------------
# 2. server side, in process
# ---------------------------------------------------------------------------------

async def asgi_call(app, method: str, path: str, body: bytes) -> tuple[int, bytes]:
    scope = {"type": "http", "asgi": {"version": "3.0"}, "http_version": "1.1",
             "method": method, "scheme": "http", "path": path, "raw_path": path.encode(),
             "query_string": b"", "root_path": "", "client": ("127.0.0.1", 50000),
             "server": ("127.0.0.1", 8000),
             "headers": [(b"host", b"127.0.0.1"), (b"content-type", b"application/json"),
                         (b"content-length", str(len(body)).encode())]}
    delivered = False
    status = 0
    chunks = []

    async def receive():
        nonlocal delivered
        if not delivered:
            delivered = True
            return {"type": "http.request", "body": body, "more_body": False}
        await asyncio.Event().wait()

    async def send(message):
        nonlocal status
        if message["type"] == "http.response.start":
            status = message["status"]
        elif message["type"] == "http.response.body":
            chunks.append(message.get("body", b""))

    await app(scope, receive, send)
    return status, b"".join(chunks)


def bench_server(rows, repeat: int) -> dict:
    from breakaway.frame import explore_frame

    app = bench_app()
    bodies = [json.dumps(b).encode() for b in slider_bodies(repeat)]

    async def run():
        timings = {"explore": [], "empty": [], "model only": []}
        for body in bodies[:10]:
            await asgi_call(app, "POST", "/api/explore", body)
        for body in bodies:
            t0 = time.perf_counter()
            status, _ = await asgi_call(app, "POST", "/api/explore", body)
            timings["explore"].append(time.perf_counter() - t0)
            assert status == 200
            t0 = time.perf_counter()
            await asgi_call(app, "POST", "/bench/empty", body)
            timings["empty"].append(time.perf_counter() - t0)
            params = json.loads(body)
            t0 = time.perf_counter()
            explore_frame(params)
            timings["model only"].append(time.perf_counter() - t0)
        return timings

    timings = asyncio.run(run())
    print("\n2. Server-side time, in process (whole ASGI app; bodies varied like slider moves)")
    for name, values in timings.items():
        print(f"   {name:28s} p50 {1e3 * pct(values, .5):6.3f} ms   p95 {1e3 * pct(values, .95):6.3f} ms")
    p50 = {name: 1e3 * pct(values, .5) for name, values in timings.items()}
    rows.append(["`/api/explore` server side, in process, p50 (of which the model)",
                 f"{p50['explore']:.2f} ms ({p50['model only']:.2f} ms)",
                 f"≤ {EXPLORE_TARGET['server_p50_ms']:g} ms"])
    return p50


# ---------------------------------------------------------------------------------
# 3. HTTP latency over loopback
# ---------------------------------------------------------------------------------

def sequential_latency(port: int, method: str, path: str, bodies: list[bytes | None],
                       repeat: int) -> list[float]:
    import http.client

    connection = http.client.HTTPConnection("127.0.0.1", port)
    times = []
    for i in range(repeat + 20):
        body = bodies[i % len(bodies)]
        t0 = time.perf_counter()
        connection.request(method, path, body=body, headers={"Content-Type": "application/json"})
        response = connection.getresponse()
        response.read()
        if i >= 20:
            times.append(time.perf_counter() - t0)
    connection.close()
    return times


def bench_http(rows, repeat: int) -> dict:
    from breakaway.params import PRESETS

    bodies = [json.dumps(b).encode() for b in slider_bodies(repeat)]
    results = {}
    print("\n3. Latency over loopback, sequential keep-alive requests (http.client)")
    for label, pure in (("uvicorn auto (httptools, uvloop)", False), ("uvicorn h11 + asyncio", True)):
        with Server(pure_python=pure) as server:
            explore = sequential_latency(server.port, "POST", "/api/explore", bodies, repeat)
            empty = sequential_latency(server.port, "POST", "/bench/empty", bodies, repeat)
            health = sequential_latency(server.port, "GET", "/api/health", [None], repeat)
            if not pure:
                sizes = []
                import http.client

                connection = http.client.HTTPConnection("127.0.0.1", server.port)
                for preset in PRESETS.values():
                    for F_hat in ("Fc", "Fs", "avg", "self"):
                        connection.request("POST", "/api/explore",
                                           body=json.dumps({**preset, "F_hat": F_hat}),
                                           headers={"Content-Type": "application/json"})
                        sizes.append(len(connection.getresponse().read()))
                connection.close()
        ratio = pct(explore, .5) / pct(empty, .5)
        print(f"   {label}:")
        for name, values in (("explore", explore), ("empty POST (floor)", empty),
                             ("GET /api/health", health)):
            print(f"     {name:26s} p50 {1e3 * pct(values, .5):6.3f} ms   p95 {1e3 * pct(values, .95):6.3f} ms")
        print(f"     explore / floor (p50)      {ratio:.2f}x")
        results[label] = ratio
        rows.append([f"latency over loopback from `http.client`, {label}: explore / empty "
                     f"POST (p50)", f"{1e3 * pct(explore, .5):.2f} / {1e3 * pct(empty, .5):.2f} "
                     f"ms = {ratio:.1f}×", "" if pure else f"≤ {EXPLORE_TARGET['floor_ratio']:g}×"])
    print(f"   payload: default {sizes[0] / 1024:.1f} KB, largest over presets × F̂ "
          f"{max(sizes) / 1024:.1f} KB (target ≤ {EXPLORE_TARGET['payload_kb']} KB)")
    rows.append(["`/api/explore` payload, default / largest preset",
                 f"{sizes[0] / 1024:.0f} / {max(sizes) / 1024:.0f} KB",
                 f"≤ {EXPLORE_TARGET['payload_kb']} KB"])
    return results


# ---------------------------------------------------------------------------------
# 4. load from a second process
# ---------------------------------------------------------------------------------

def bench_load(rows, duration: float, count: int) -> None:
    bodies = json.dumps(slider_bodies(64))
    print(f"\n4. Load from a second process on 127.0.0.1: 32 connections, "
          f"≤ {count} requests or ≤ {duration:g} s each")
    with Server() as server:
        for label, args in (("explore (varied bodies)", ["--bodies", bodies]),
                            ("empty POST (floor)", ["--path", "/bench/empty"])):
            output = subprocess.run(
                [sys.executable, str(HERE / "loadgen.py"), "--port", str(server.port),
                 "--concurrency", "32", "--duration", str(duration), "--count", str(count),
                 *args], capture_output=True, text=True, timeout=duration + 60, check=True)
            result = json.loads(output.stdout)
            print(f"   {label:26s} {result['rate']:7.0f} req/s  errors {result['errors']}  "
                  f"({result['requests']} in {result['seconds']:.1f} s; latency p50 "
                  f"{result['p50_ms']:.1f} ms, p95 {result['p95_ms']:.1f} ms)")
            rows.append([f"load, 32 connections from a second process: {label}",
                         f"{result['rate']:.0f} req/s, {result['errors']} errors",
                         f"≥ {EXPLORE_TARGET['rate']} req/s" if "explore" in label else ""])


# ---------------------------------------------------------------------------------
# 5. the browser
# ---------------------------------------------------------------------------------

MEASURE_INPUTS = """
async ({moves, newPlot}) => {
  if (newPlot && !window.__reactOriginal) {
    window.__reactOriginal = Plotly.react;
    Plotly.react = (gd, data, layout, config) => {
      Plotly.purge(gd);
      return Plotly.newPlot(gd, data, layout, config);
    };
  }
  const fetched = [];
  const originalFetch = window.fetch;
  window.fetch = async (...args) => {
    const response = await originalFetch(...args);
    fetched.push(performance.now());
    return response;
  };
  const frame = () => new Promise((resolve) => requestAnimationFrame(() => resolve()));
  const out = [];
  for (const [id, position] of moves) {
    await frame();
    const slider = document.getElementById(id + '-range');
    const t0 = performance.now();
    fetched.length = 0;
    slider.value = String(position);
    slider.dispatchEvent(new Event('input', {bubbles: true}));
    // a click on the slider: released at once, so the page settles without waiting for
    // the hand to rest (its live frame is benchmarks/ui_latency.py's)
    slider.dispatchEvent(new Event('change', {bubbles: true}));
    await window.breakaway.ready();
    const drawn = performance.now();
    await frame();
    out.push({total: drawn - t0, request: fetched[0] - t0, draw: drawn - fetched[0],
              painted: performance.now() - t0});
  }
  window.fetch = originalFetch;
  return out;
}
"""

FETCH_LATENCY = """
async ({bodies, repeat}) => {
  const time = async (path, body) => {
    const t0 = performance.now();
    const response = await fetch(path, {method: 'POST', body,
                                        headers: {'Content-Type': 'application/json'}});
    await response.json();
    return performance.now() - t0;
  };
  const out = {explore: [], empty: []};
  for (let i = 0; i < repeat + 10; i++) {
    const body = bodies[i % bodies.length];
    const explore = await time('/api/explore', body);
    const empty = await time('/bench/empty', body);
    if (i >= 10) { out.explore.push(explore); out.empty.push(empty); }
  }
  return out;
}
"""

SLIDER_POSITIONS = {"Fc": (400, 500), "Fs": (500, 600), "V": (600, 800), "delta": (90, 140),
                    "sigma": (0, 500), "k": (0, 1000), "s": (200, 400), "z_ba": (50, 97)}


def bench_browser(rows, repeat: int) -> None:
    from playwright.sync_api import sync_playwright

    chromium = os.environ.get("BREAKAWAY_CHROMIUM") or (
        "/usr/bin/chromium" if Path("/usr/bin/chromium").exists() else None)
    rng = random.Random(11)
    names = list(SLIDER_POSITIONS)
    moves = [[names[i % len(names)], rng.randint(*SLIDER_POSITIONS[names[i % len(names)]])]
             for i in range(repeat + 20)]
    print(f"\n5. Browser: slider input to all four plots redrawn ({repeat} inputs, "
          f"{len(names)} sliders in turn, Chromium headless, 1280×800)")
    with Server() as server, sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=chromium, headless=True,
            args=["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync"])
        page = browser.new_page()
        page.goto(f"{server.url}/?sim=0")
        bodies = [json.dumps(b) for b in slider_bodies(64)]
        fetched = page.evaluate(FETCH_LATENCY, {"bodies": bodies, "repeat": repeat})
        page.close()
        explore, empty = fetched["explore"], fetched["empty"]
        print(f"   fetch() + response.json() from the page: explore p50 {pct(explore, .5):5.2f} ms, "
              f"empty POST p50 {pct(empty, .5):5.2f} ms: {pct(explore, .5) / pct(empty, .5):.2f}x "
              f"the floor")
        rows.append(["latency from the page's `fetch`: explore / empty POST (p50)",
                     f"{pct(explore, .5):.2f} / {pct(empty, .5):.2f} ms = "
                     f"{pct(explore, .5) / pct(empty, .5):.1f}×",
                     f"≤ {EXPLORE_TARGET['floor_ratio']:g}×"])
        for label, new_plot in (("Plotly.react (explorer)", False),
                                ("Plotly.purge + newPlot", True)):
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            page.goto(f"{server.url}/?sim=0")
            page.evaluate("window.breakaway.ready()")
            runs = page.evaluate(MEASURE_INPUTS, {"moves": moves, "newPlot": new_plot})[20:]
            page.close()
            total = [r["total"] for r in runs]
            print(f"   {label:26s} p50 {pct(total, .5):6.1f} ms  p95 {pct(total, .95):6.1f} ms"
                  f"  (request p50 {pct([r['request'] for r in runs], .5):5.1f} ms, drawing "
                  f"p50 {pct([r['draw'] for r in runs], .5):5.1f} ms; to the next frame p50 "
                  f"{pct([r['painted'] for r in runs], .5):5.1f} ms)")
            rows.append([f"a click on a slider → the settled plots, Chromium, {label} (p50 / p95)",
                         f"{pct(total, .5):.1f} / {pct(total, .95):.1f} ms",
                         f"≤ {EXPLORE_TARGET['browser_p50_ms']} / "
                         f"≤ {EXPLORE_TARGET['browser_p95_ms']} ms" if not new_plot else ""])
        browser.close()


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="fewer repetitions")
    parser.add_argument("--only", default="serial,server,http,load,browser")
    parser.add_argument("--serve", type=int, help=argparse.SUPPRESS)
    parser.add_argument("--pure-python", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.serve:
        serve(args.serve, args.pure_python)
        return 0
    sections = set(args.only.split(","))
    repeat = 60 if args.quick else 300
    out, rows = Results("explorer", __file__), []
    print(f"Explorer benchmarks on {machine()}")
    print(f"load average at start: {load_average()}")
    if "serial" in sections:
        bench_serial(rows, repeat)
    if "server" in sections:
        bench_server(rows, repeat)
    if "http" in sections:
        bench_http(rows, repeat)
    if "load" in sections:
        bench_load(rows, duration=3.0 if args.quick else 8.0, count=1000 if args.quick else 4000)
    if "browser" in sections:
        bench_browser(rows, 60 if args.quick else 200)
    print()
    out.table(["figure", "measured", "target"], rows)
    out.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
