"""A lecture hall on one server: students drag sliders while three recordings are fitted.

    .venv/bin/python benchmarks/bench_lecture.py [--seconds 20] [--students 48] [--fits 3]
                                                 [--rounds 1]

The server (``breakaway serve``, as a teacher starts it) gets, for ``--seconds``:

- ``--students`` explorer clients, each on its own keep-alive connection, sending
  ``POST /api/explore`` with a slider moved, then pausing 100–300 ms (a person dragging);
- a health probe, ``GET /api/health`` on a fresh connection every 0.5 s;
- ``--fits`` uploads of a 15 MB recording (420,000 rows with two effects), sent together
  two seconds in (the lecturer: "now upload yours") through ``POST /api/fit/jobs``,
  polled once a second and sent again when their fit has ended. The server fits two at
  a time (``BREAKAWAY_FIT_WORKERS=2``); the third waits for a worker.

Printed per configuration: explore requests, errors, p50/p99/worst latency; health p99
and worst; uploads accepted and the seconds their answers took, fits finished; the
second (of the measurement) that held most of the slowest answers; the load average.
The configurations, each on a fresh server, in turn within one run (``--rounds``
times, so that the machine's other load falls on each):

- the server as it ships: uploads parsed in a reader process and fitted in worker
  processes, both at niceness 10;
- the reader and the fit workers at the server's priority (``BREAKAWAY_FIT_NICENESS=0``),
  the obvious alternative;
- uploads parsed in the server's threads, as before the reader process (parse_csv holds
  the interpreter's lock for about a second per 15 MB, and the event loop waits for it).

Targets: explore p99 ≤ 250 ms, health ≤ 250 ms at the worst, 0 errors. The clients are
asyncio in this process; on a 2-core machine they share its CPU with the server, as a
real lecture hall's clients would not.
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
TARGETS = {"p99_ms": 250, "health_ms": 250}
#: Rows of the uploaded recording: 15 MB as CSV.
ROWS = 420_000
#: Seconds of students before the uploads arrive.
UPLOADS_AT_S = 2.0
#: label: (environment, uploads parsed in the server's threads)
CONFIGURATIONS = {
    "as shipped": ({}, False),
    "reader and fit workers at the server's priority": ({"BREAKAWAY_FIT_NICENESS": "0"},
                                                         False),
    "uploads parsed in the server's threads": ({}, True),
}


def recording() -> bytes:
    sys.path.insert(0, str(ROOT / "backend"))
    from breakaway.identify.synthetic import make_dataset, to_csv

    return to_csv(make_dataset("timeseries", ("viscous", "ripple"), seed=3, n=ROWS)[0]).encode()


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


async def once(port: int, method: str, path: str, body: bytes = b"",
               content_type: str = "application/json"):
    """One request on a connection of its own: (status, body)."""
    status, answer, (_, writer) = await http("127.0.0.1", port, method, path, body, content_type)
    writer.close()
    return status, answer


async def student(port, bodies, started, deadline, stats, rng):
    conn = None
    while time.monotonic() < deadline:
        body = orjson.dumps(rng.choice(bodies))
        sent = time.perf_counter()
        try:
            status, _, conn = await http("127.0.0.1", port, "POST", "/api/explore", body, conn=conn)
            if status != 200:
                stats["errors"] += 1
        except (OSError, ConnectionError, asyncio.IncompleteReadError):
            stats["errors"] += 1
            conn = None
        stats["explore"].append((sent - started, 1000 * (time.perf_counter() - sent)))
        await asyncio.sleep(rng.uniform(0.1, 0.3))
    if conn:
        conn[1].close()


def upload(content: bytes) -> tuple[bytes, str]:
    """A multipart form with ``content`` as its file: (body, content type)."""
    boundary = "lecturehall"
    body = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
            f"filename=\"recording.csv\"\r\nContent-Type: text/csv\r\n\r\n").encode() \
        + content + f"\r\n--{boundary}--\r\n".encode()
    return body, f"multipart/form-data; boundary={boundary}"


async def fitter(port, content, deadline, stats):
    body, content_type = upload(content)
    while time.monotonic() < deadline:
        sent = time.perf_counter()
        status, answer = await once(port, "POST", "/api/fit/jobs", body, content_type)
        if status != 202:
            stats["fit_refused"] += 1
            await asyncio.sleep(1.0)
            continue
        stats["uploads"].append(time.perf_counter() - sent)
        job = orjson.loads(answer)["id"]
        while time.monotonic() < deadline:
            await asyncio.sleep(1.0)
            _, answer = await once(port, "GET", f"/api/fit/jobs/{job}")
            if orjson.loads(answer)["status"] not in ("queued", "running"):
                stats["fits_done"] += 1
                break


async def prober(port, started, deadline, stats):
    while time.monotonic() < deadline:
        sent = time.perf_counter()
        try:
            status, _ = await once(port, "GET", "/api/health")
            if status != 200:
                stats["errors"] += 1
        except OSError:
            stats["errors"] += 1
        stats["health"].append((sent - started, 1000 * (time.perf_counter() - sent)))
        await asyncio.sleep(0.5)


async def lecture(port, seconds, students, fits, content) -> dict:
    stats = {"explore": [], "health": [], "errors": 0, "uploads": [], "fits_done": 0,
             "fit_refused": 0}
    bodies = slider_bodies(256)
    started = time.perf_counter()
    deadline = time.monotonic() + seconds
    rng = random.Random(5)
    tasks = [asyncio.create_task(student(port, bodies, started, deadline, stats,
                                         random.Random(rng.random())))
             for _ in range(students)]
    tasks.append(asyncio.create_task(prober(port, started, deadline, stats)))
    await asyncio.sleep(UPLOADS_AT_S)
    uploads = [asyncio.create_task(fitter(port, content, deadline, stats)) for _ in range(fits)]
    await asyncio.gather(*tasks)
    for task in uploads:
        task.cancel()
    return stats


def serve(env: dict[str, str], threads: bool, data_dir: str) -> tuple[subprocess.Popen, int]:
    port = free_port()
    command = [sys.executable, "-m", "breakaway", "serve", "--port", str(port)]
    if threads:
        command = [sys.executable, str(Path(__file__).resolve()), "--serve-parsing-in-threads",
                   str(port)]
    process = subprocess.Popen(
        command, env={**os.environ, **env, "BREAKAWAY_DATA_DIR": data_dir},
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.monotonic() + 60
    while True:
        try:
            urllib.request.urlopen(f"http://127.0.0.1:{port}/api/health", timeout=1).read()
            break
        except OSError:
            if time.monotonic() > deadline:
                raise RuntimeError("server did not start")
            time.sleep(0.1)
    asyncio.run(warm(port))
    return process, port


async def warm(port: int) -> None:
    """Wait for the server's workers to be warm, as they are by the time a lecture
    starts: the simulator answers, and the upload reader refuses an empty file."""
    assert (await once(port, "POST", "/api/simulate", b'{"k": [1.0]}'))[0] == 200
    assert (await once(port, "POST", "/api/fit", *upload(b"")))[0] == 422


def serve_parsing_in_threads(port: int) -> None:
    """The former server: the same app, with each upload parsed in a thread of its own."""
    import uvicorn
    from fastapi.concurrency import run_in_threadpool

    from breakaway.api import fitworkers
    from breakaway.api.app import create_app
    from breakaway.identify import parse_csv

    async def in_thread(self, content, kind, max_bytes):
        return await run_in_threadpool(parse_csv, content, kind, max_bytes)

    fitworkers.FitWorkers.read = in_thread
    uvicorn.run(create_app(), host="127.0.0.1", port=port, log_level="warning")


def slowest_second(samples) -> str:
    """When the slowest answers came: the second of the measurement holding the most of
    the slowest 1 %."""
    worst = sorted(samples, key=lambda s: s[1])[-max(1, len(samples) // 100):]
    seconds = [int(at) for at, _ in worst]
    second = max(set(seconds), key=seconds.count)
    return f"{seconds.count(second)} of the slowest {len(worst)} in second {second}"


def report(label: str, stats: dict, seconds: float) -> str:
    explore = [ms for _, ms in stats["explore"]]
    health = [ms for _, ms in stats["health"]]
    return (f"  {label}: explore {len(explore)} requests ({len(explore) / seconds:.0f}/s), "
            f"p50 {pct(explore, .5):.1f} ms, p99 {pct(explore, .99):.1f} ms, worst "
            f"{max(explore):.0f} ms; health p99 {pct(health, .99):.1f} ms, worst "
            f"{max(health):.1f} ms; errors {stats['errors']}; uploads {len(stats['uploads'])} "
            f"(answered in {' '.join(f'{s:.1f}' for s in sorted(stats['uploads']))} s), "
            f"fits finished {stats['fits_done']}, refused {stats['fit_refused']}; "
            f"{slowest_second(stats['explore'] + stats['health'])} "
            f"(load average {load_average()})")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--students", type=int, default=48)
    parser.add_argument("--fits", type=int, default=3)
    parser.add_argument("--rounds", type=int, default=1)
    parser.add_argument("--serve-parsing-in-threads", type=int, default=None,
                        help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.serve_parsing_in_threads:
        serve_parsing_in_threads(args.serve_parsing_in_threads)
        return 0
    content = recording()
    out, rows = Results("lecture", __file__), []
    print(f"{args.students} students (100–300 ms between requests) + a health probe, "
          f"{args.seconds:g} s; {args.fits} uploads of {len(content) / 1e6:.1f} MB "
          f"({ROWS:,} rows) at {UPLOADS_AT_S:g} s, fitting; targets: explore p99 ≤ "
          f"{TARGETS['p99_ms']} ms, health ≤ {TARGETS['health_ms']} ms, 0 errors")
    for _ in range(args.rounds):
        for label, (env, threads) in CONFIGURATIONS.items():
            with tempfile.TemporaryDirectory() as data_dir:
                process, port = serve(env, threads, data_dir)
                try:
                    stats = asyncio.run(lecture(port, args.seconds, args.students, args.fits,
                                                content))
                finally:
                    os.killpg(process.pid, signal.SIGTERM)
                    process.wait(120)  # an upload still being read is let finish
            print(report(label, stats, args.seconds), flush=True)
            explore = [ms for _, ms in stats["explore"]]
            health = [ms for _, ms in stats["health"]]
            rows.append([label, f"{len(explore) / args.seconds:.0f}/s",
                         f"{pct(explore, .5):.1f} / {pct(explore, .99):.1f} ms",
                         f"{pct(health, .99):.0f} / {max(health):.0f} ms", stats["errors"],
                         f"{stats['fits_done']} (refused {stats['fit_refused']})"])
    print()
    out.table(["server", "explore requests", "explore p50 / p99", "health p99 / worst",
               "errors", "fits finished"], rows)
    out.note(f"{args.students} explorer clients (100–300 ms between requests) and a health "
             f"probe for {args.seconds:g} s; {args.fits} uploads of "
             f"{len(content) / 1e6:.1f} MB arrive together {UPLOADS_AT_S:g} s in and fit. "
             f"Targets: explore p99 ≤ {TARGETS['p99_ms']} ms, health ≤ "
             f"{TARGETS['health_ms']} ms at the worst, 0 errors.")
    out.write()
    return 0


if __name__ == "__main__":
    sys.exit(main())
