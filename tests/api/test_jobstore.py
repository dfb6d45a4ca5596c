"""The fit jobs' SQLite store on its own: capacity, progress and cancel, results, the
bounds by age and bytes, and jobs a dead server left behind."""

from __future__ import annotations

import os
import sqlite3
import subprocess
import sys

import pytest

from breakaway.api.jobstore import JobStore


@pytest.fixture
def store(tmp_path):
    return JobStore(tmp_path / "data" / "jobs.sqlite")


def test_capacity_counts_this_process_active_jobs(store):
    first, second = store.create("a.csv", capacity=2), store.create("b.csv", capacity=2)
    assert first and second and first != second
    assert store.create("c.csv", capacity=2) is None
    store.finish(first, "done", report={"kind": "steady"})
    assert store.create("c.csv", capacity=2) is not None
    assert store.active() == 2 and store.active(owner=os.getpid()) == 2


def test_progress_cancel_and_results(store):
    job = store.create("a.csv", capacity=1)
    assert not store.running(job)  # queued until its worker writes progress
    assert store.progress(job, 0.25, "fitting the base model") is False
    assert store.get(job)["status"] == "running" and store.get(job)["progress"] == 0.25
    assert store.running(job)
    assert store.request_cancel(job) is True
    assert store.progress(job, 0.5, "next") is True  # the worker learns of the cancel
    store.finish(job, "cancelled")
    assert not store.running(job) and not store.running("nope")
    cancelled = store.get(job)
    assert cancelled["status"] == "cancelled" and cancelled["progress"] == 0.5
    assert store.request_cancel("nope") is False

    done = store.create("b.csv", capacity=1)
    store.finish(done, "done", report={"kind": "steady", "n": 3}, series={"axis": "v"},
                 residuals="v,F\n1,2\n")
    job = store.get(done)
    assert job["report"] == {"kind": "steady", "n": 3} and job["series"] == {"axis": "v"}
    assert job["residuals"] == "v,F\n1,2\n" and job["progress"] == 1.0
    assert job["size"] == len(b'{"kind":"steady","n":3}') + len(b'{"axis":"v"}') + len("v,F\n1,2\n")


def test_bounds_by_age_and_by_bytes(tmp_path):
    store = JobStore(tmp_path / "jobs.sqlite", max_bytes=100, max_age_s=3600)
    old, big, running = (store.create(name, capacity=5) for name in ("old", "big", "run"))
    store.finish(old, "done", residuals="x" * 10)
    store.finish(big, "done", residuals="y" * 150)
    with sqlite3.connect(store.path) as db:
        db.execute("UPDATE jobs SET updated = updated - 7200 WHERE id = ?", (old,))
    store.prune()
    assert store.get(old) is None  # past its age
    assert store.get(big) is None  # over the byte bound, the oldest finished first
    assert store.get(running)["status"] == "queued"  # active jobs are never dropped


def test_jobs_of_a_dead_server_are_reported(store):
    job = store.create("a.csv", capacity=1)
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)
    with sqlite3.connect(store.path) as db:
        db.execute("UPDATE jobs SET owner = ? WHERE id = ?", (int(dead.stdout), job))
    mine = store.create("b.csv", capacity=1)
    assert store.abandon_orphans() == 1
    assert store.get(job)["status"] == "error" and "restarted" in store.get(job)["error"]
    assert store.get(mine)["status"] == "queued"
