"""A small HTTP/1.1 load generator for 127.0.0.1 (run as its own process).

``concurrency`` keep-alive connections each send requests back to back until ``count``
requests are done or ``duration`` seconds have passed, whichever is first. The client
is raw asyncio streams so that it costs far less CPU than the server it measures.
Prints one JSON object: requests, errors, seconds, rate, latency percentiles [ms].
"""

from __future__ import annotations

import argparse
import asyncio
import json
import random
import sys
import time


def request_bytes(method: str, path: str, body: bytes) -> bytes:
    head = (f"{method} {path} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: keep-alive\r\n"
            f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n\r\n")
    return head.encode() + body


async def read_response(reader: asyncio.StreamReader) -> int:
    status_line = await reader.readline()
    if not status_line:
        raise ConnectionError("connection closed")
    status = int(status_line.split()[1])
    length = None
    while True:
        line = await reader.readline()
        if line in (b"\r\n", b""):
            break
        name, _, value = line.partition(b":")
        if name.strip().lower() == b"content-length":
            length = int(value)
    if length is None:
        raise ValueError("no content-length")
    await reader.readexactly(length)
    return status


async def client(host, port, requests, deadline, budget, stats):
    reader, writer = await asyncio.open_connection(host, port)
    try:
        while time.perf_counter() < deadline and budget[0] > 0:
            budget[0] -= 1
            payload = random.choice(requests)
            start = time.perf_counter()
            writer.write(payload)
            try:
                status = await read_response(reader)
            except (ConnectionError, ValueError, asyncio.IncompleteReadError):
                stats["errors"] += 1
                reader, writer = await asyncio.open_connection(host, port)
                continue
            stats["latencies"].append(time.perf_counter() - start)
            if status != 200:
                stats["errors"] += 1
    finally:
        writer.close()


async def run(args) -> dict:
    bodies = json.loads(args.bodies) if args.bodies else [None]
    requests = [request_bytes(args.method, args.path,
                              b"" if body is None else json.dumps(body).encode())
                for body in bodies]
    stats = {"errors": 0, "latencies": []}
    start = time.perf_counter()
    deadline = start + args.duration
    budget = [args.count]
    await asyncio.gather(*(client(args.host, args.port, requests, deadline, budget, stats)
                           for _ in range(args.concurrency)))
    seconds = time.perf_counter() - start
    latencies = sorted(stats["latencies"])

    def pct(q):
        return 1e3 * latencies[min(len(latencies) - 1, int(q * len(latencies)))] if latencies else None

    return {"requests": len(latencies), "errors": stats["errors"], "seconds": seconds,
            "rate": len(latencies) / seconds, "p50_ms": pct(0.5), "p95_ms": pct(0.95),
            "p99_ms": pct(0.99), "concurrency": args.concurrency}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, required=True)
    parser.add_argument("--method", default="POST")
    parser.add_argument("--path", default="/api/explore")
    parser.add_argument("--bodies", default="", help="JSON list of request bodies to cycle")
    parser.add_argument("--concurrency", type=int, default=32)
    parser.add_argument("--duration", type=float, default=10.0, help="at most this long [s]")
    parser.add_argument("--count", type=int, default=5000, help="at most this many requests")
    args = parser.parse_args(argv)
    if args.host not in ("127.0.0.1", "localhost", "::1"):
        parser.error("loopback only")
    print(json.dumps(asyncio.run(run(args))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
