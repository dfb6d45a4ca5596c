"""The fit jobs' store: one SQLite file under the data directory.

Every server process on the same data directory (``breakaway serve --workers N``) and
every fit worker process reads and writes it, so a page's poll can land on any of them,
a cancel reaches the process that runs the job, and finished results outlive a restart.
SQLite in WAL mode takes one writer at a time and readers beside it, which is all the
traffic here: a progress row a few times a second per running fit, a poll per page per
second.

The store is bounded: finished jobs older than ``max_age_s`` are dropped, then the
oldest finished ones until the results take at most ``max_bytes``.
"""

from __future__ import annotations

import os
import sqlite3
import time
import uuid
from contextlib import closing
from pathlib import Path

import orjson

ACTIVE = ("queued", "running")

_SCHEMA = """
CREATE TABLE IF NOT EXISTS jobs (
    id TEXT PRIMARY KEY,
    source TEXT NOT NULL,
    status TEXT NOT NULL,           -- queued | running | done | error | cancelled
    progress REAL NOT NULL DEFAULT 0,
    message TEXT NOT NULL DEFAULT '',
    error TEXT,
    report BLOB,                    -- JSON
    series BLOB,                    -- JSON
    residuals BLOB,                 -- CSV text
    size INTEGER NOT NULL DEFAULT 0,
    cancel INTEGER NOT NULL DEFAULT 0,
    owner INTEGER,                  -- pid of the server process that runs it
    created REAL NOT NULL,
    updated REAL NOT NULL
);
CREATE INDEX IF NOT EXISTS jobs_status ON jobs(status);
"""


class JobStore:
    """Fit jobs in SQLite at ``path`` (created with its folder)."""

    def __init__(self, path: Path, max_bytes: int = 256 * 2**20, max_age_s: float = 86_400.0):
        self.path = Path(path)
        self.max_bytes = max_bytes
        self.max_age_s = max_age_s
        self.path.parent.mkdir(parents=True, exist_ok=True)
        with closing(self._connect()) as db:
            db.execute("PRAGMA journal_mode=WAL")
            db.executescript(_SCHEMA)

    def _connect(self) -> sqlite3.Connection:
        # autocommit; a writer waits up to 10 s for another process's write to end
        db = sqlite3.connect(self.path, timeout=10.0, isolation_level=None)
        db.row_factory = sqlite3.Row
        return db

    # -- the server's side -------------------------------------------------------------

    def create(self, source: str, capacity: int) -> str | None:
        """A new queued job owned by this process, or None when ``capacity`` jobs of this
        process are already queued or running (checked and inserted in one transaction)."""
        now = time.time()
        job_id = uuid.uuid4().hex
        with closing(self._connect()) as db:
            db.execute("BEGIN IMMEDIATE")
            (active,) = db.execute(
                f"SELECT COUNT(*) FROM jobs WHERE owner = ? AND status IN {ACTIVE}",
                (os.getpid(),)).fetchone()
            if active >= capacity:
                db.execute("ROLLBACK")
                return None
            db.execute("INSERT INTO jobs (id, source, status, message, owner, created, updated)"
                       " VALUES (?, ?, 'queued', 'waiting for a worker', ?, ?, ?)",
                       (job_id, source, os.getpid(), now, now))
            db.execute("COMMIT")
        self.prune()
        return job_id

    def active(self, owner: int | None = None) -> int:
        """Jobs queued or running (of one server process, or of all)."""
        query = f"SELECT COUNT(*) FROM jobs WHERE status IN {ACTIVE}"
        args: tuple = ()
        if owner is not None:
            query += " AND owner = ?"
            args = (owner,)
        with closing(self._connect()) as db:
            return db.execute(query, args).fetchone()[0]

    def get(self, job_id: str) -> dict | None:
        with closing(self._connect()) as db:
            row = db.execute("SELECT * FROM jobs WHERE id = ?", (job_id,)).fetchone()
        if row is None:
            return None
        job = dict(row)
        for key in ("report", "series"):
            job[key] = orjson.loads(job[key]) if job[key] is not None else None
        if job["residuals"] is not None:
            job["residuals"] = job["residuals"].decode()
        return job

    def request_cancel(self, job_id: str) -> bool:
        """Mark an active job to be cancelled; whether there is such a job at all."""
        with closing(self._connect()) as db:
            db.execute(f"UPDATE jobs SET cancel = 1, message = 'cancelling', updated = ? "
                       f"WHERE id = ? AND status IN {ACTIVE}", (time.time(), job_id))
            return db.execute("SELECT 1 FROM jobs WHERE id = ?", (job_id,)).fetchone() is not None

    def cancel_requested(self, job_id: str) -> bool:
        with closing(self._connect()) as db:
            row = db.execute("SELECT cancel FROM jobs WHERE id = ?", (job_id,)).fetchone()
        return bool(row and row[0])

    def running(self, job_id: str) -> bool:
        """Whether the job's worker has begun it (written its first progress)."""
        with closing(self._connect()) as db:
            row = db.execute("SELECT status FROM jobs WHERE id = ?", (job_id,)).fetchone()
        return bool(row and row[0] == "running")

    def abandon_orphans(self) -> int:
        """Jobs left queued or running by a server process that is gone (a restart, a
        crash) end as errors, so no page polls them forever."""
        with closing(self._connect()) as db:
            rows = db.execute(f"SELECT id, owner FROM jobs WHERE status IN {ACTIVE}").fetchall()
            gone = [row["id"] for row in rows if not _alive(row["owner"])]
            for job_id in gone:
                self.finish(job_id, "error", error="the server restarted during this fit; "
                                                   "start it again", db=db)
        return len(gone)

    # -- the worker's side -------------------------------------------------------------

    def progress(self, job_id: str, fraction: float, message: str) -> bool:
        """Record progress (the job is running); whether a cancel was asked for."""
        with closing(self._connect()) as db:
            db.execute("UPDATE jobs SET status = 'running', progress = ?, message = ?, "
                       "updated = ? WHERE id = ? AND status IN ('queued', 'running')",
                       (round(min(max(fraction, 0.0), 1.0), 3), message, time.time(), job_id))
            row = db.execute("SELECT cancel FROM jobs WHERE id = ?", (job_id,)).fetchone()
        return bool(row and row[0])

    def finish(self, job_id: str, status: str, *, report: dict | None = None,
               series: dict | None = None, residuals: str | None = None,
               error: str | None = None, db: sqlite3.Connection | None = None) -> None:
        blobs = [orjson.dumps(report, option=orjson.OPT_SERIALIZE_NUMPY) if report is not None else None,
                 orjson.dumps(series, option=orjson.OPT_SERIALIZE_NUMPY) if series is not None else None,
                 residuals.encode() if residuals is not None else None]
        size = sum(len(b) for b in blobs if b is not None)
        message = {"done": "done", "cancelled": "cancelled"}.get(status, "failed")
        # a finished fit shows 100 %; a stopped one keeps the progress it had
        query = ("UPDATE jobs SET status = ?, progress = COALESCE(?, progress), message = ?, "
                 "error = ?, report = ?, series = ?, residuals = ?, size = ?, updated = ? "
                 "WHERE id = ?")
        args = (status, 1.0 if status == "done" else None, message, error, *blobs, size,
                time.time(), job_id)
        if db is not None:
            db.execute(query, args)
            return
        with closing(self._connect()) as own:
            own.execute(query, args)

    # -- bounds ------------------------------------------------------------------------

    def prune(self) -> None:
        """Drop finished jobs past their age, then the oldest until under the byte bound."""
        with closing(self._connect()) as db:
            db.execute("BEGIN IMMEDIATE")
            db.execute(f"DELETE FROM jobs WHERE status NOT IN {ACTIVE} AND updated < ?",
                       (time.time() - self.max_age_s,))
            (total,) = db.execute("SELECT COALESCE(SUM(size), 0) FROM jobs").fetchone()
            if total > self.max_bytes:
                rows = db.execute(f"SELECT id, size FROM jobs WHERE status NOT IN {ACTIVE} "
                                  "ORDER BY updated").fetchall()
                for row in rows:
                    if total <= self.max_bytes:
                        break
                    db.execute("DELETE FROM jobs WHERE id = ?", (row["id"],))
                    total -= row["size"]
            db.execute("COMMIT")

    def total_bytes(self) -> int:
        with closing(self._connect()) as db:
            return db.execute("SELECT COALESCE(SUM(size), 0) FROM jobs").fetchone()[0]


def _alive(pid: int | None) -> bool:
    if not pid:
        return False
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
