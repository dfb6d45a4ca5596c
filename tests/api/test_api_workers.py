"""Fits and simulations in worker processes, as a lecture hall meets them: a cancel frees
the CPU within a second (DELETE, or the client of POST /api/fit leaving), the time limit
counts from the start of the work, the queue is bounded, jobs live in SQLite across a
restart and across two server processes, a burst of oversize uploads leaves the memory
alone, a client that leaves mid-simulation leaves the next requests answered and the log
clean, and a shutdown ends every worker and leaks nothing."""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import socket
import sqlite3
import subprocess
import sys
import threading
import time
import urllib.request
from pathlib import Path

import numpy as np
import orjson
import pytest
from fastapi.testclient import TestClient

from breakaway.api.app import create_app
from breakaway.api.fitworkers import FitWorkers
from breakaway.api.jobstore import JobStore
from breakaway.dynamics import simulate_breakaway
from breakaway.identify import parse_csv
from breakaway.identify.synthetic import make_dataset, to_csv
from breakaway.params import DEFAULTS
from breakaway.settings import get_settings
from settings_override import overridden_settings

from coroutines import run_to_end

#: A fit of about 7 s here (two effects on 40,000 rows).
LONG = to_csv(make_dataset("timeseries", ("viscous", "ripple"), seed=3, n=40_000)[0]).encode()
SHORT = to_csv(make_dataset("steady", (), seed=1)[0]).encode()
TICK = os.sysconf("SC_CLK_TCK")


def upload(content: bytes, name: str = "data.csv") -> dict:
    return {"file": (name, content, "text/csv")}


def cpu_seconds(pids) -> float:
    total = 0
    for pid in pids:
        try:
            fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
        except FileNotFoundError:
            continue
        total += int(fields[11]) + int(fields[12])  # utime, stime
    return total / TICK


def children(pid: int) -> list[int]:
    """Every descendant process of ``pid``."""
    parents = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                parents[int(entry.name)] = int(
                    (entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            except (FileNotFoundError, ProcessLookupError):
                pass
    out, frontier = [], [pid]
    while frontier:
        parent = frontier.pop()
        kids = [p for p, pp in parents.items() if pp == parent]
        out += kids
        frontier += kids
    return out


def alive(pid: int) -> bool:
    """Whether the process runs (a zombie nobody reaped does not)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except (FileNotFoundError, ProcessLookupError):
        return False


def spawned(parent: int) -> set[int]:
    """The running worker processes ``parent`` spawned (not multiprocessing's resource
    tracker)."""
    found = set()
    for pid in children(parent):
        try:
            if alive(pid) and b"spawn_main" in Path(f"/proc/{pid}/cmdline").read_bytes():
                found.add(pid)
        except (FileNotFoundError, ProcessLookupError):
            pass
    return found


def assert_idle(pids, seconds: float = 1.0) -> None:
    before = cpu_seconds(pids)
    time.sleep(seconds)
    assert cpu_seconds(pids) - before < 0.1 * seconds


def wait_status(get, job_id: str, wanted: set[str], timeout: float) -> dict:
    deadline = time.monotonic() + timeout
    while True:
        job = get(job_id)
        if job["status"] in wanted:
            return job
        assert time.monotonic() < deadline, f"job {job_id} still {job['status']}"
        time.sleep(0.05)


@pytest.fixture
def app_with(tmp_path):
    """A TestClient on an app with these settings and its own data directory."""
    with contextlib.ExitStack() as stack:

        def make(**settings) -> TestClient:
            stack.enter_context(overridden_settings(data_dir=tmp_path / "data", **settings))
            return stack.enter_context(TestClient(create_app()))

        yield make


def test_a_cancelled_job_frees_the_cpu_within_a_second(app_with):
    client = app_with()
    get = lambda job_id: client.get(f"/api/fit/jobs/{job_id}").json()  # noqa: E731
    job = client.post("/api/fit/jobs", files=upload(LONG, "long.csv")).json()
    running = wait_status(get, job["id"], {"running"}, timeout=30)
    assert running["progress"] >= 0.0
    time.sleep(1.0)  # well into the fit
    workers = children(os.getpid())
    assert cpu_seconds(workers) > 0.3  # it was computing
    asked = time.monotonic()
    assert client.delete(f"/api/fit/jobs/{job['id']}").status_code == 200
    ended = wait_status(get, job["id"], {"cancelled"}, timeout=5)
    assert time.monotonic() - asked < 1.0
    assert ended["report"] is None
    assert_idle(workers)


def test_the_time_limit_counts_from_the_start_and_the_queue_is_bounded(app_with):
    client = app_with(fit_workers=1, fit_queue=1, fit_timeout_s=2.0)
    get = lambda job_id: client.get(f"/api/fit/jobs/{job_id}").json()  # noqa: E731
    slow = client.post("/api/fit/jobs", files=upload(LONG, "long.csv")).json()
    waiting = client.post("/api/fit/jobs", files=upload(SHORT, "short.csv")).json()
    assert waiting["status"] == "queued"
    # a third fit finds the worker and the queue taken: refused before its upload is read
    refused = client.post("/api/fit/jobs", files=upload(b"not even read"))
    assert refused.status_code == 429 and refused.headers["retry-after"] == "5"
    stopped = wait_status(get, slow["id"], {"done", "error", "cancelled"}, timeout=30)
    assert stopped["status"] == "error" and "longer than 2 s" in stopped["error"]
    # the short fit waited about 2 s for the worker, then had its own 2 s
    done = wait_status(get, waiting["id"], {"done", "error", "cancelled"}, timeout=30)
    assert done["status"] == "done", done["error"]
    assert done["report"]["kind"] == "steady"


def test_jobs_outlive_a_restart_of_the_app(app_with):
    first = app_with()
    job = first.post("/api/fit/jobs", files=upload(SHORT, "short.csv")).json()
    done = wait_status(lambda i: first.get(f"/api/fit/jobs/{i}").json(), job["id"], {"done"}, 60)
    first.__exit__(None, None, None)
    second = app_with()
    again = second.get(f"/api/fit/jobs/{job['id']}").json()
    assert again["status"] == "done" and again["report"] == done["report"]
    residuals = second.get(f"/api/fit/jobs/{job['id']}/residuals.csv")
    assert residuals.headers["content-type"].startswith("text/csv")
    header = [line for line in residuals.text.splitlines() if not line.startswith("#")][0]
    assert header.startswith("v,")


def test_the_store_is_bounded_by_bytes(app_with):
    client = app_with(jobs_max_bytes=1)  # every finished result is over the bound
    get = lambda job_id: client.get(f"/api/fit/jobs/{job_id}")  # noqa: E731
    first = client.post("/api/fit/jobs", files=upload(SHORT, "a.csv")).json()
    wait_status(lambda i: get(i).json(), first["id"], {"done"}, 60)
    second = client.post("/api/fit/jobs", files=upload(SHORT, "b.csv")).json()
    assert get(first["id"]).status_code == 404  # pruned when the next job came
    wait_status(lambda i: get(i).json(), second["id"], {"done"}, 60)
    store = client.app.state.fit_workers.store
    store.prune()
    assert store.total_bytes() == 0


def test_uploads_are_read_in_a_reader_process_replaced_when_it_dies(tmp_path, caplog):
    workers = FitWorkers(JobStore(tmp_path / "jobs.sqlite"))
    big = to_csv(make_dataset("timeseries", ("viscous",), seed=4, n=300_000)[0]).encode()
    limit = 2 * len(big)
    expected = parse_csv(SHORT)
    before = spawned(os.getpid())
    try:
        read = run_to_end(workers.read(SHORT, None, limit))
        assert read.kind == "steady"
        np.testing.assert_array_equal(read.columns["F"], expected.columns["F"])
        [first] = spawned(os.getpid()) - before
        # killed while idle: the next upload is read by a new reader
        os.kill(first, signal.SIGKILL)
        while alive(first):
            time.sleep(0.01)
        read = run_to_end(workers.read(SHORT, None, limit))
        np.testing.assert_array_equal(read.columns["v"], expected.columns["v"])
        [second] = spawned(os.getpid()) - before

        async def killed_midway():
            idle = cpu_seconds([second])
            reading = asyncio.ensure_future(workers.read(big, None, limit))
            # killed once it is parsing (15 MB take about a second of its CPU): a fixed
            # sleep could miss the parse on a loaded machine
            deadline = time.monotonic() + 30
            while cpu_seconds([second]) - idle < 0.1 and not reading.done() \
                    and time.monotonic() < deadline:
                await asyncio.sleep(0.01)
            assert not reading.done(), "the upload was read before the reader was killed"
            os.kill(second, signal.SIGKILL)
            return await reading

        # killed while it parsed: the upload is read again by a third
        assert run_to_end(killed_midway()).n == 300_000
        assert len(spawned(os.getpid()) - before - {second}) == 1
        assert caplog.text.count("the upload reader died (attempt 1") == 2
    finally:
        workers.shutdown()
    assert not spawned(os.getpid()) - before


# ---------------------------------------------------------------------------------
# real server processes
# ---------------------------------------------------------------------------------


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


class Server:
    """``breakaway serve`` in its own session, its log (stderr) in a file."""

    def __init__(self, data_dir: Path, workers: int = 1):
        self.port = free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.log_path = data_dir.parent / f"server-{self.port}.log"
        data_dir.parent.mkdir(parents=True, exist_ok=True)
        env = {**os.environ, "BREAKAWAY_DATA_DIR": str(data_dir)}
        with open(self.log_path, "wb") as log:
            self.process = subprocess.Popen(
                [sys.executable, "-m", "breakaway", "serve", "--port", str(self.port),
                 "--workers", str(workers)], env=env, stdout=subprocess.DEVNULL,
                stderr=log, start_new_session=True)
        deadline = time.monotonic() + 60
        while True:
            try:
                self.get("/api/health")
                break
            except OSError:
                assert self.process.poll() is None, "the server exited"
                assert time.monotonic() < deadline, "the server did not start"
                time.sleep(0.1)

    def get(self, path: str):
        with urllib.request.urlopen(self.url + path, timeout=10) as response:
            return orjson.loads(response.read())

    def request(self, method: str, path: str, body: bytes = b"", headers=None):
        request = urllib.request.Request(self.url + path, data=body or None, method=method,
                                         headers=headers or {})
        try:
            with urllib.request.urlopen(request, timeout=120) as response:
                return response.status, response.read()
        except urllib.error.HTTPError as err:
            return err.code, err.read()

    def post_file(self, path: str, content: bytes, name: str = "data.csv"):
        boundary = "breakawaytestboundary"
        body = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
                f"filename=\"{name}\"\r\nContent-Type: text/csv\r\n\r\n").encode() + content \
            + f"\r\n--{boundary}--\r\n".encode()
        return self.request("POST", path, body,
                            {"Content-Type": f"multipart/form-data; boundary={boundary}"})

    def rss_mb(self, workers: bool = False) -> float:
        """Resident memory of the server process, or of its worker processes [MB]."""
        pids = children(self.process.pid) if workers else [self.process.pid]
        total = 0
        for pid in pids:
            for line in Path(f"/proc/{pid}/status").read_text().splitlines():
                if line.startswith("VmRSS:"):
                    total += int(line.split()[1])
        return total / 1024

    def stop(self, sig=signal.SIGTERM):
        os.killpg(self.process.pid, sig)
        self.process.wait(timeout=20)

    def shut_down(self, sig: int, group: bool) -> tuple[int, str]:
        """Stop the server with ``sig`` (to its whole process group, as a terminal's
        Ctrl+C does, or to the server alone, as ``docker stop`` does); its exit code and
        its log once every process it started has ended (the resource tracker writes
        its leak report last)."""
        started = children(self.process.pid)
        (os.killpg if group else os.kill)(self.process.pid, sig)
        code = self.process.wait(timeout=30)
        deadline = time.monotonic() + 10
        while [pid for pid in started if alive(pid)]:
            assert time.monotonic() < deadline, "a worker outlived the server"
            time.sleep(0.05)
        return code, self.log_path.read_text()


@pytest.fixture
def servers(tmp_path):
    started = []

    def start(workers: int = 1) -> Server:
        server = Server(tmp_path / "data", workers)
        started.append(server)
        return server

    yield start
    for server in started:
        if server.process.poll() is None:
            server.stop(signal.SIGKILL)


def store_rows(tmp_path: Path) -> list[dict]:
    with sqlite3.connect(tmp_path / "data" / "jobs.sqlite") as db:
        db.row_factory = sqlite3.Row
        return [dict(row) for row in db.execute("SELECT id, source, status FROM jobs")]


def test_a_client_that_leaves_stops_its_fit(servers, tmp_path):
    server = servers()
    boundary = "b0undary"
    body = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
            f"filename=\"left.csv\"\r\nContent-Type: text/csv\r\n\r\n").encode() + LONG \
        + f"\r\n--{boundary}--\r\n".encode()
    head = (f"POST /api/fit HTTP/1.1\r\nHost: 127.0.0.1:{server.port}\r\n"
            f"Content-Type: multipart/form-data; boundary={boundary}\r\n"
            f"Content-Length: {len(body)}\r\n\r\n").encode()
    with socket.create_connection(("127.0.0.1", server.port)) as sock:
        sock.sendall(head + body)
        deadline = time.monotonic() + 30
        while not [r for r in store_rows(tmp_path) if r["status"] == "running"]:
            assert time.monotonic() < deadline
            time.sleep(0.05)
        time.sleep(1.0)
    left = time.monotonic()
    while [r for r in store_rows(tmp_path) if r["status"] == "running"]:
        assert time.monotonic() - left < 1.5, "the fit went on after its client left"
        time.sleep(0.05)
    assert [r["status"] for r in store_rows(tmp_path)] == ["cancelled"]
    assert_idle([server.process.pid] + children(server.process.pid))


def test_jobs_outlive_a_restart_and_a_running_one_is_reported(servers):
    first = servers()
    status, body = first.post_file("/api/fit/jobs", SHORT, "short.csv")
    assert status == 202
    done_id = orjson.loads(body)["id"]
    wait_status(lambda i: first.get(f"/api/fit/jobs/{i}"), done_id, {"done"}, 60)
    status, body = first.post_file("/api/fit/jobs", LONG, "long.csv")
    running_id = orjson.loads(body)["id"]
    wait_status(lambda i: first.get(f"/api/fit/jobs/{i}"), running_id, {"running"}, 30)
    first.stop(signal.SIGKILL)  # no shutdown: a crash, or a pulled plug

    second = servers()
    assert second.get(f"/api/fit/jobs/{done_id}")["status"] == "done"
    interrupted = second.get(f"/api/fit/jobs/{running_id}")
    assert interrupted["status"] == "error" and "restarted" in interrupted["error"]


def test_two_server_processes_share_the_jobs(servers):
    server = servers(workers=2)
    answered = set()
    deadline = time.monotonic() + 30
    while len(answered) < 2:
        answered.add(server.get("/api/health")["worker"])
        assert time.monotonic() < deadline, "one process answered every request"
    status, body = server.post_file("/api/fit/jobs", SHORT, "short.csv")
    job_id = orjson.loads(body)["id"]
    seen = set()
    while True:
        job = server.get(f"/api/fit/jobs/{job_id}")  # a new connection each time
        seen.add(job["status"])
        if job["status"] == "done":
            break
        time.sleep(0.02)
    assert seen <= {"queued", "running", "done"}
    for _ in range(10):  # whichever process answers has the result
        assert server.get(f"/api/fit/jobs/{job_id}")["report"]["kind"] == "steady"
    # a cancel sent to either process reaches the one that runs the fit
    status, body = server.post_file("/api/fit/jobs", LONG, "long.csv")
    job_id = orjson.loads(body)["id"]
    wait_status(lambda i: server.get(f"/api/fit/jobs/{i}"), job_id, {"running"}, 30)
    assert server.request("DELETE", f"/api/fit/jobs/{job_id}")[0] == 200
    wait_status(lambda i: server.get(f"/api/fit/jobs/{i}"), job_id, {"cancelled"}, 2.0)


def test_memory_returns_after_oversize_uploads_and_finished_fits(servers):
    server = servers()
    server.get("/api/health")
    baseline = server.rss_mb()
    limit = get_settings().max_upload_bytes
    just_over = b"v,F\n" + b"1" * (limit + 1 - 4)  # read and measured, then refused
    far_over = b"v,F\n" + b"1" * (limit + 5 * 2**20)  # refused by its Content-Length
    answers = []

    def send(content):
        # as a browser does: the whole body goes out unless the server answers first
        boundary = "b0undary"
        body = (f"--{boundary}\r\nContent-Disposition: form-data; name=\"file\"; "
                f"filename=\"big.csv\"\r\nContent-Type: text/csv\r\n\r\n").encode() \
            + content + f"\r\n--{boundary}--\r\n".encode()
        head = (f"POST /api/fit HTTP/1.1\r\nHost: 127.0.0.1:{server.port}\r\n"
                f"Content-Type: multipart/form-data; boundary={boundary}\r\n"
                f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n").encode()
        with socket.create_connection(("127.0.0.1", server.port), timeout=60) as sock:
            sock.sendall(head)
            try:
                sock.sendall(body)
            except OSError:  # refused mid-body: the answer is already on its way
                pass
            answer = b""
            try:
                while b"\r\n" not in answer:
                    chunk = sock.recv(4096)
                    if not chunk:
                        break
                    answer += chunk
            except OSError:
                pass
        answers.append(int(answer.split()[1]) if answer.startswith(b"HTTP/1.1") else None)

    threads = [threading.Thread(target=send, args=(content,))
               for content in (just_over, far_over) * 3]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert answers == [413] * 6
    time.sleep(0.5)
    assert server.rss_mb() - baseline < 150
    # and after finished fits: their results are in the store, not in the server; the
    # fit processes, once started, stay as large as their first fit left them
    medium = to_csv(make_dataset("timeseries", ("viscous",), seed=5, n=20_000)[0]).encode()
    for _ in range(2):  # one fit in each of the two fit processes
        assert server.post_file("/api/fit", medium, "medium.csv")[0] == 200
    warm = server.rss_mb(workers=True)
    for _ in range(4):
        assert server.post_file("/api/fit", medium, "medium.csv")[0] == 200
    time.sleep(0.5)
    assert server.rss_mb() - baseline < 150
    assert server.rss_mb(workers=True) - warm < 150


#: What a clean log never holds: an exception nobody read (the pool's error for a run its
#: client left), a traceback (a worker killed by a signal meant for the server), and the
#: resource tracker's report of semaphores or memory a pool did not release.
UNCLEAN = ("never retrieved", "BrokenProcessPool", "Traceback", "KeyboardInterrupt",
           "resource_tracker", "leaked", "worker died")


def test_a_simulation_its_client_left_is_ended_and_the_log_stays_clean(servers):
    server = servers()
    # a damper fitted in kN under the note's N/s rates: none breaks away, each rate
    # takes its whole step budget (about 0.7 s here), 40 rates about half a minute
    rates = [round(0.01 * 1.1 ** i, 6) for i in range(40)]
    body = orjson.dumps({"k": rates, "Fc": 15430, "Fs": 16320, "V": 1.704e-4,
                         "delta": 7.3, "s": 53.6, "max_steps": 1_000_000})
    head = (f"POST /api/simulate HTTP/1.1\r\nHost: 127.0.0.1:{server.port}\r\n"
            f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n\r\n").encode()
    # both workers warm: the simulator answers, and the upload reader refuses an empty file
    simulate = orjson.dumps({"k": [1.0, 4.0]})
    json = {"Content-Type": "application/json"}
    assert server.request("POST", "/api/simulate", simulate, json)[0] == 200
    assert server.post_file("/api/fit", b"")[0] == 422
    workers = spawned(server.process.pid)
    with socket.create_connection(("127.0.0.1", server.port)) as sock:
        sock.sendall(head + body)
        time.sleep(1.5)
    time.sleep(1.0)  # the server notices within a second
    assert_idle([server.process.pid] + children(server.process.pid))
    # the simulation worker was ended in its run (a finished run leaves it be); the
    # reader was left alone
    assert len(workers - spawned(server.process.pid)) == 1
    # the next requests are served by one fresh worker, with the model's values
    params = {name: DEFAULTS[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "m",
                                                  "z_ba")}
    expected = simulate_breakaway([1.0, 4.0], **params, max_steps=1_000_000)
    for _ in range(3):
        status, answer = server.request("POST", "/api/simulate", simulate, json)
        assert status == 200
        assert orjson.loads(answer)["u_ba"] == pytest.approx(expected.u_ba.tolist(), rel=1e-12)
    status, answer = server.request("POST", "/api/ramp", orjson.dumps({"k": 4.0}), json)
    assert status == 200
    assert orjson.loads(answer)["u_ba"] == pytest.approx(expected.u_ba[1], rel=1e-12)
    assert len(spawned(server.process.pid)) == 2
    code, log = server.shut_down(signal.SIGINT, group=True)
    assert code == 0
    assert not [line for line in log.splitlines() if any(word in line for word in UNCLEAN)]


@pytest.mark.parametrize("sig, group", [(signal.SIGINT, True), (signal.SIGTERM, False)],
                         ids=["ctrl-c-to-the-group", "sigterm-to-the-server"])
def test_a_shutdown_ends_every_worker_and_leaks_nothing(servers, tmp_path, sig, group):
    server = servers()
    status, _ = server.request("POST", "/api/simulate", orjson.dumps({"k": [1.0]}),
                               {"Content-Type": "application/json"})
    assert status == 200
    # a fit done in one fit worker, one cancelled in the other (its process ended), and
    # one running in the first at the shutdown
    assert server.post_file("/api/fit", SHORT, "short.csv")[0] == 200
    get = lambda job_id: server.get(f"/api/fit/jobs/{job_id}")  # noqa: E731
    cancelled = orjson.loads(server.post_file("/api/fit/jobs", LONG, "long.csv")[1])["id"]
    wait_status(get, cancelled, {"running"}, 30)
    assert server.request("DELETE", f"/api/fit/jobs/{cancelled}")[0] == 200
    wait_status(get, cancelled, {"cancelled"}, 5)
    running = orjson.loads(server.post_file("/api/fit/jobs", LONG, "long.csv")[1])["id"]
    wait_status(get, running, {"running"}, 30)
    # the simulation worker, the upload reader and the fit slots' processes: the
    # cancelled fit's ended, and the running fit may have been handed that slot (a fresh
    # process) while the first fit's stays idle in the other: one or two
    assert 3 <= len(spawned(server.process.pid)) <= 4
    code, log = server.shut_down(sig, group)
    # uvicorn shuts down in order, then raises a SIGTERM again to end with it
    assert code == (0 if sig == signal.SIGINT else -signal.SIGTERM)
    assert "Application shutdown complete" in log
    assert not [line for line in log.splitlines() if any(word in line for word in UNCLEAN)]
