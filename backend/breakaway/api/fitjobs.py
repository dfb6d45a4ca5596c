"""Fit jobs: the identification runs in worker threads, off the event loop, with
progress a page can poll and a cancel that stops the job at its next checkpoint."""

from __future__ import annotations

import threading
import uuid
from collections import OrderedDict
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

from ..identify import DataError, Dataset, FitError, diagnose, report
from ..identify.panel import residuals_csv, series


class Cancelled(Exception):
    """Raised inside a job's progress callback once the job is cancelled."""


class Busy(Exception):
    """All workers are taken."""


@dataclass
class FitJob:
    id: str
    source: str
    status: str = "queued"  # queued | running | done | error | cancelled
    progress: float = 0.0
    message: str = "waiting for a worker"
    report: dict | None = None
    series: dict | None = None
    residuals: str | None = None
    error: str | None = None
    cancel_event: threading.Event = field(default_factory=threading.Event)


class FitJobs:
    """A bounded store of fit jobs run by a small thread pool."""

    def __init__(self, workers: int = 2, keep: int = 32):
        self._pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="fit")
        self._workers = workers
        self._keep = keep
        self._jobs: OrderedDict[str, FitJob] = OrderedDict()
        self._lock = threading.Lock()

    def full(self) -> bool:
        """Whether every worker is taken (a new job would be refused)."""
        with self._lock:
            return sum(j.status in ("queued", "running") for j in self._jobs.values()) >= self._workers

    def submit(self, data: Dataset, source: str) -> FitJob:
        with self._lock:
            active = sum(j.status in ("queued", "running") for j in self._jobs.values())
            if active >= self._workers:
                raise Busy(f"{active} fits are already running; try again when one ends")
            job = FitJob(uuid.uuid4().hex, source)
            self._jobs[job.id] = job
            while len(self._jobs) > self._keep:
                oldest = next(iter(self._jobs))
                if self._jobs[oldest].status in ("queued", "running"):
                    break
                self._jobs.pop(oldest)
        self._pool.submit(self._run, job, data)
        return job

    def get(self, job_id: str) -> FitJob | None:
        return self._jobs.get(job_id)

    def cancel(self, job_id: str) -> FitJob | None:
        job = self._jobs.get(job_id)
        if job is not None and job.status in ("queued", "running"):
            job.cancel_event.set()
            job.message = "cancelling"
        return job

    def shutdown(self) -> None:
        for job in self._jobs.values():
            job.cancel_event.set()
        self._pool.shutdown(wait=False, cancel_futures=True)

    @staticmethod
    def _run(job: FitJob, data: Dataset) -> None:
        def progress(fraction: float, message: str) -> None:
            if job.cancel_event.is_set():
                raise Cancelled
            job.progress = round(min(max(fraction, 0.0), 1.0), 3)
            job.message = message

        try:
            progress(0.0, "starting")
            job.status = "running"
            diagnosis = diagnose(data, progress)
            job.report = report(diagnosis)
            job.series = series(diagnosis)
            job.residuals = residuals_csv(diagnosis)
            job.progress, job.message, job.status = 1.0, "done", "done"
        except Cancelled:
            job.status, job.message = "cancelled", "cancelled"
        except (DataError, FitError) as err:
            job.status, job.error, job.message = "error", str(err), "failed"
        except Exception as err:  # a job must end in a state the page can show
            job.status, job.error, job.message = "error", f"fit failed: {err}", "failed"
