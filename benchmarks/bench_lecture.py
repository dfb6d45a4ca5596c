"""A lecture hall on one server: students drag sliders while two recordings are fitted.

    .venv/bin/python benchmarks/bench_lecture.py [--seconds 20] [--students 48]

The server (``breakaway serve``, as a teacher starts it) gets, for ``--seconds``:

- ``--students`` explorer clients, each on its own keep-alive connection, sending
  ``POST /api/explore`` with a slider moved, then pausing 100–300 ms (a person dragging);
- two fits of a 40,000-row recording with two effects (about 7 s each here), started
  again as soon as one ends, through ``POST /api/fit/jobs`` and polled once a second;
- a health probe, ``GET /api/health`` on a fresh connection every 0.5 s.

Printed: explore requests, errors, p50/p99 latency; health worst and p99; fits done. The
same load is run against the server as it was, with the fits in the server's own
threads, by ``--fits-in-threads`` (the obvious alternative: no worker processes); the
two figures are printed together. Targets: explore p50 ≤ 50 ms, p99 ≤ 250 ms, health
≤ 250 ms at the worst, 0 errors. The client is asyncio in this process; on this 2-core machine it
shares the CPU with the server, as a real lecture hall's clients would not.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path

import orjson

from bench_explorer import free_port, load_average, machine, pct, slider_bodies
from results import Results

ROOT = Path(__file__).resolve().parents[1]
TARGETS = {"p50_ms": 50, "p99_ms": 250, "health_ms": 250}


def recording() -> bytes:
    sys.path.insert(0, str(ROOT / "backend"))
    from breakaway.identify.synthetic import make_dataset, to_csv

    return to_csv(make_dataset("timeseries", ("viscous", "ripple"), seed=3, n=40_000)[0]).encode()


async def http(host: str, port: int, method: str, path: str, body: bytes = b"",
               content_type: str = "application/json", conn=None):
    """One request; ``conn`` = (reader, writer) to reuse. Returns (status, body, conn)."""
    if conn is None:
        conn = await asyncio.open_connection(host, port)
    reader, writer = conn
    head = (f"{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
            f"Content-Type: {content_type}\r\nContent-Length: {len(body)}\r\n\r\n")
    writer.write(head.encode() + body)
    await writer.drain()
    status_line = await reader.readline()
    if not status_line:
        raise ConnectionError("closed")
    status = int(status_line.split()[1])
    length = 0
    while True:
        line = await reader.readline()
        if line in (b"\r\n", b""):
            break
        name, _, value = line.partition(b":")
        if name.strip().lower() == b"content-length":
            length = int(value)
    return status, await reader.readexactly(length), conn


async def student(port, bodies, deadline, stats, rng):
    conn = None
    while time.monotonic() < deadline:
        body = orjson.dumps(rng.choice(bodies))
        started = time.perf_counter()
        try:
            status, _, conn = await http("127.0.0.1", port, "POST", "/api/explore", body, conn=conn)
            if status != 200:
                stats["errors"] += 1
        except (OSError, ConnectionError, asyncio.IncompleteReadError):
            stats["errors"] += 1
            conn = None
        stats["explore"].append(1000 * (time.perf_counter() - started))
        await asyncio.sleep(rng.uniform(0.1, 0.3))
    if conn:
        conn[1].close()


async def fitter(port, content, deadline, stats):
    boundary = "lecturehall"
    body = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
            f"filename=\"recording.csv\"\r\nContent-Type: text/csv\r\n\r\n").encode() \
        + content + f"\r\n--{boundary}--\r\n".encode()
    while time.monotonic() < deadline:
        status, answer, conn = await http("127.0.0.1", port, "POST", "/api/fit/jobs", body,
                                          f"multipart/form-data; boundary={boundary}")
        conn[1].close()
        if status != 202:
            stats["fit_refused"] += 1
            await asyncio.sleep(1.0)
            continue
        job = orjson.loads(answer)["id"]
        while time.monotonic() < deadline:
            await asyncio.sleep(1.0)
            status, answer, conn = await http("127.0.0.1", port, "GET", f"/api/fit/jobs/{job}")
            conn[1].close()
            if orjson.loads(answer)["status"] not in ("queued", "running"):
                stats["fits_done"] += 1
                break
        else:
            await http("127.0.0.1", port, "DELETE", f"/api/fit/jobs/{job}")


async def prober(port, deadline, stats):
    while time.monotonic() < deadline:
        started = time.perf_counter()
        try:
            status, _, conn = await http("127.0.0.1", port, "GET", "/api/health")
            conn[1].close()
            if status != 200:
                stats["errors"] += 1
        except OSError:
            stats["errors"] += 1
        stats["health"].append(1000 * (time.perf_counter() - started))
        await asyncio.sleep(0.5)


async def lecture(port, seconds, students, content) -> dict:
    stats = {"explore": [], "health": [], "errors": 0, "fits_done": 0, "fit_refused": 0}
    bodies = slider_bodies(256)
    # the fits start first, as if two recordings were uploaded just before
    deadline = time.monotonic() + seconds
    fits = [asyncio.create_task(fitter(port, content, deadline, stats)) for _ in range(2)]
    await asyncio.sleep(2.0)
    deadline = time.monotonic() + seconds
    rng = random.Random(5)
    tasks = [asyncio.create_task(student(port, bodies, deadline, stats, random.Random(rng.random())))
             for _ in range(students)]
    tasks.append(asyncio.create_task(prober(port, deadline, stats)))
    await asyncio.gather(*tasks)
    for task in fits:
        task.cancel()
    return stats


def serve(threads: bool, data_dir: str) -> tuple[subprocess.Popen, int]:
    port = free_port()
    env = {**os.environ, "BREAKAWAY_DATA_DIR": data_dir}
    command = [sys.executable, "-m", "breakaway", "serve", "--port", str(port)]
    if threads:
        command = [sys.executable, str(Path(__file__).resolve()), "--serve-threads", str(port)]
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + 60
    while True:
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/api/health", timeout=1).read()
            return process, port
        except OSError:
            if time.monotonic() > deadline:
                raise RuntimeError("server did not start")
            time.sleep(0.1)


def serve_with_fits_in_threads(port: int) -> None:
    """The alternative: the same app, with each fit run in a thread of the server."""
    import uvicorn
    from fastapi.concurrency import run_in_threadpool

    from breakaway.api import fitworkers
    from breakaway.api.app import create_app

    async def in_thread(self, job_id, data, gone=None):
        await run_in_threadpool(fitworkers.run_fit, str(self.store.path), job_id, data)

    fitworkers.FitWorkers.run = in_thread
    uvicorn.run(create_app(), host="127.0.0.1", port=port, log_level="warning")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--students", type=int, default=48)
    parser.add_argument("--serve-threads", type=int, default=None, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.serve_threads:
        serve_with_fits_in_threads(args.serve_threads)
        return 0
    print(f"Machine: {machine()}")
    print(f"{args.students} students (100–300 ms between requests) + 2 fits + a health probe, "
          f"{args.seconds:g} s; targets: explore p50 ≤ {TARGETS['p50_ms']} ms, "
          f"p99 ≤ {TARGETS['p99_ms']} ms, health ≤ {TARGETS['health_ms']} ms, 0 errors")
    content = recording()
    out, rows = Results("lecture", __file__), []
    for label, threads in (("fits in worker processes (the server)", False),
                           ("fits in the server's threads", True)):
        with tempfile.TemporaryDirectory() as data_dir:
            process, port = serve(threads, data_dir)
            try:
                stats = asyncio.run(lecture(port, args.seconds, args.students, content))
            finally:
                os.killpg(process.pid, signal.SIGTERM)
                process.wait(20)
        explore, health = stats["explore"], stats["health"]
        print(f"  {label}: explore {len(explore)} requests "
              f"({len(explore) / args.seconds:.0f}/s), p50 {pct(explore, .5):.1f} ms, "
              f"p99 {pct(explore, .99):.1f} ms; health p99 {pct(health, .99):.1f} ms, "
              f"worst {max(health):.1f} ms; errors {stats['errors']}; fits finished "
              f"{stats['fits_done']}, refused {stats['fit_refused']} "
              f"(load average {load_average()})")
        rows.append([label, f"{len(explore) / args.seconds:.0f}/s",
                     f"{pct(explore, .5):.1f} / {pct(explore, .99):.1f} ms",
                     f"{pct(health, .99):.0f} / {max(health):.0f} ms", stats["errors"],
                     f"{stats['fits_done']} (refused {stats['fit_refused']})"])
    print()
    out.table(["fits run in", "explore requests", "explore p50 / p99", "health p99 / worst",
               "errors", "fits finished"], rows)
    out.note(f"{args.students} explorer clients (100–300 ms between requests), two fits of a "
             f"40,000-row recording kept running and a health probe, {args.seconds:g} s. "
             f"Targets: explore p50 ≤ {TARGETS['p50_ms']} ms, p99 ≤ {TARGETS['p99_ms']} ms, "
             f"health ≤ {TARGETS['health_ms']} ms at the worst, 0 errors.")
    out.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
