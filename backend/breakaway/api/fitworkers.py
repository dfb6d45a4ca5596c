"""Fits in a bounded pool of worker processes, off the server's process.

A fit holds the CPU (and, in its compiled parts, the GIL) for seconds to minutes: in the
server's own threads it starved the explorer's requests. Here each of ``workers`` slots
is one worker process; ``queue`` more fits may wait for a slot; a fit beyond that is
refused (429) before its upload is read. A fit's time limit starts when it starts
running, not while it waits. A cancel (``DELETE``, or the client of ``POST /api/fit``
going away) is seen within a quarter second: the fit stops at its next progress
checkpoint, and a fit still running half a second later has its worker process ended,
so the CPU is free within a second either way.

Uploads are parsed in a reader process of their own, started with the server (a fit
slot may be busy for minutes, and the page waits for the answer): ``parse_csv`` holds
the interpreter's lock for about a second per 15 MB, which in a thread of the server
held its event loop as long. The reader runs at the fits' niceness: at the server's
priority it still took the CPU from the event loop while three uploads were read
(benchmarks/bench_lecture.py).

Jobs, their progress and their results live in the :class:`~.jobstore.JobStore`, which
the worker processes write and every server process reads.
"""

from __future__ import annotations

import asyncio
import logging
import os
import time
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path
from typing import Awaitable, Callable

from ..identify import DataError, Dataset, FitError, diagnose, parse_csv, report
from ..identify.panel import residuals_csv, series
from .jobstore import JobStore
from .processes import WorkerProcess

log = logging.getLogger("breakaway.api")

#: Seconds between looks at a running fit's cancel flag and client.
POLL_S = 0.25
#: Seconds a cancelled fit gets to stop at a checkpoint before its process is ended.
GRACE_S = 0.5
#: Seconds between progress rows a worker writes (a cancel is read with each).
PROGRESS_EVERY_S = 0.2
#: Seconds a fresh fit worker may take to start (import the engine) before its fit's
#: time limit begins anyway.
START_S = 60.0


class Cancelled(Exception):
    """Raised inside a fit's progress callback once its job is cancelled."""


def run_fit(db_path: str, job_id: str, data: Dataset) -> None:
    """Worker entry point: diagnose ``data`` and write the outcome into the store."""
    store = JobStore(Path(db_path))
    last = None  # when progress was last written

    def progress(fraction: float, message: str) -> None:
        nonlocal last
        now = time.monotonic()
        if last is not None and now - last < PROGRESS_EVERY_S:
            return
        last = now
        if store.progress(job_id, fraction, message):
            raise Cancelled

    try:
        progress(0.0, "starting")
        diagnosis = diagnose(data, progress)
        store.finish(job_id, "done", report=report(diagnosis), series=series(diagnosis),
                     residuals=residuals_csv(diagnosis))
    except Cancelled:
        store.finish(job_id, "cancelled")
    except (DataError, FitError) as err:
        store.finish(job_id, "error", error=str(err))
    except Exception:  # a job ends in a state the page can show, without internals
        log.exception("fit %s failed", job_id)
        store.finish(job_id, "error", error="the fit failed on these data; the server log "
                                            "has the details")


def _imported() -> None:
    """Nothing: a worker that runs it has imported this module, and the engine with it."""


class FitWorkers:
    """``workers`` fit processes and a waiting room of ``queue``, over one job store, and
    the upload reader; the processes run at ``niceness`` (added to the server's)."""

    def __init__(self, store: JobStore, workers: int = 2, queue: int = 2,
                 timeout_s: float = 600.0, niceness: int = 10) -> None:
        self.store = store
        self.capacity = workers + queue
        self.timeout_s = timeout_s
        self._slots = [WorkerProcess(niceness) for _ in range(workers)]
        self._reader = WorkerProcess(niceness)  # parses the uploads
        self._free: asyncio.Queue[WorkerProcess] | None = None
        self._tasks: set[asyncio.Task] = set()
        #: the running fits' watchers in this process, woken by a cancel
        self._cancelled: dict[str, asyncio.Event] = {}

    def cancel(self, job_id: str) -> None:
        """Ask a queued or running fit to stop (``DELETE /api/fit/jobs/{id}``): its flag in
        the store, which its worker reads at its next progress, and its watcher in this
        process woken now, not at its next poll."""
        self.store.request_cancel(job_id)
        event = self._cancelled.get(job_id)
        if event is not None:
            event.set()

    def full(self) -> bool:
        """Whether this server process already has as many fits as it takes."""
        return self.store.active(owner=os.getpid()) >= self.capacity

    def create(self, source: str) -> str | None:
        """A queued job, or None when the pool and its queue are full."""
        return self.store.create(source, self.capacity)

    def start_reader(self) -> None:
        """Start the upload reader now: it imports the identification engine (seconds),
        which the first upload would otherwise wait for."""
        self._reader.warm_up(_imported)

    async def read(self, content: bytes, kind: str | None, max_bytes: int) -> Dataset:
        """``parse_csv(content, kind, max_bytes)`` in the reader process; its
        :class:`DataError` as it raises it. A reader that died is replaced once."""
        for attempt in (1, 2):
            try:
                return await asyncio.wrap_future(
                    self._reader.submit(parse_csv, content, kind, max_bytes))
            except BrokenProcessPool:
                self._reader.end()
                log.warning("the upload reader died (attempt %d, a %d-byte file)", attempt,
                            len(content))
        raise DataError("the server could not read this file (out of memory?); try again "
                        "or send a smaller file")

    def start(self, job_id: str, data: Dataset) -> None:
        """Run the job in the background (``POST /api/fit/jobs``)."""
        task = asyncio.get_running_loop().create_task(self.run(job_id, data))
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    async def run(self, job_id: str, data: Dataset,
                  gone: Callable[[], Awaitable[bool]] | None = None) -> None:
        """Run the job in a free slot and return when it has ended (done, error or
        cancelled). ``gone``: whether the client that waits for it has left."""
        if self._free is None:
            self._free = asyncio.Queue()
            for slot in self._slots:
                self._free.put_nowait(slot)
        slot = await self._free.get()
        try:
            await self._watch(slot, job_id, data, gone)
        finally:
            self._free.put_nowait(slot)

    async def _watch(self, slot: WorkerProcess, job_id: str, data: Dataset, gone) -> None:
        store = self.store
        if store.cancel_requested(job_id) or (gone and await gone()):
            store.finish(job_id, "cancelled")
            return
        loop = asyncio.get_running_loop()
        # the time limit counts from the fit's first progress in its worker, not from the
        # queue nor from a fresh worker's start-up (its imports take seconds on a busy
        # machine); a worker that never begins is stopped START_S after the limit
        submitted = loop.time()
        future = asyncio.wrap_future(slot.submit(run_fit, str(store.path), job_id, data))
        # a fit whose process was ended still resolves its future (broken pool): read it
        future.add_done_callback(lambda f: f.cancelled() or f.exception())
        del data  # the worker has its copy; the server keeps none
        cancelled = self._cancelled[job_id] = asyncio.Event()
        woken = asyncio.ensure_future(cancelled.wait())
        try:
            await self._follow(slot, job_id, future, woken, gone, submitted)
        finally:
            woken.cancel()
            self._cancelled.pop(job_id, None)

    async def _follow(self, slot: WorkerProcess, job_id: str, future, woken, gone,
                      submitted: float) -> None:
        store = self.store
        loop = asyncio.get_running_loop()
        begun = stop_at = None
        while True:
            # a cancel through this process wakes the watcher at once; one through
            # another is seen at the next poll. Once seen, the next look is at the end of
            # its grace: a cancel ends within GRACE_S (0.5 s; POLL_S more through
            # another process) plus the time to end the worker, inside the second it is
            # promised (a poll after the grace had taken it to 1.0 s and past)
            wait = POLL_S if stop_at is None else max(0.0, min(POLL_S, stop_at - loop.time()))
            watched = {future} if stop_at is not None or woken.done() else {future, woken}
            done, _ = await asyncio.wait(watched, timeout=wait,
                                         return_when=asyncio.FIRST_COMPLETED)
            if future in done:
                try:
                    future.result()
                except BrokenProcessPool:
                    slot.end()
                    if stop_at is None:
                        log.warning("fit worker died during job %s", job_id)
                        store.finish(job_id, "error", error="the fit's worker process died "
                                                            "(out of memory?)")
                    else:
                        store.finish(job_id, "cancelled")
                return
            now = loop.time()
            if stop_at is None and (store.cancel_requested(job_id) or (gone and await gone())):
                store.request_cancel(job_id)
                stop_at = now + GRACE_S
            if stop_at is not None and now >= stop_at:
                slot.end()  # did not reach a checkpoint in time: end its process
                store.finish(job_id, "cancelled")
                return
            if begun is None and store.running(job_id):
                begun = now
            if now - (submitted + START_S if begun is None else begun) > self.timeout_s:
                slot.end()
                store.finish(job_id, "error", error=f"the fit took longer than "
                                                    f"{self.timeout_s:g} s and was stopped")
                return

    def shutdown(self) -> None:
        for task in self._tasks:
            task.cancel()
        for worker in (*self._slots, self._reader):
            worker.end()
