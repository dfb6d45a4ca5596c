"""The server's worker processes: each one started on demand, owned by the server for
its whole life, and ended whole.

Simulations and fits run in worker processes so that their CPU time never holds the
server's event loop; a run is stopped at once by ending its process. Three things make
that clean:

- The server alone ends its workers. A Ctrl+C in a terminal (SIGINT) or a service
  manager's stop (SIGTERM) reaches every process of the group: a worker ignores both,
  from before Python starts in it (the signals are held while it is spawned), so it
  does not die mid-fit with a traceback while the server shuts down in order. A worker
  whose server was killed outright ends itself within a second.
- Ending a worker releases what its pool holds: five named semaphores (the locks of
  its two queues). uvicorn ends a server on SIGTERM by raising the signal again once
  its shutdown is done, so no exit handler runs after it; a pool not released by then
  leaves the resource tracker to report "leaked semaphore objects".
- A worker's scheduling priority is set in the worker, before its first task.
"""

from __future__ import annotations

import contextlib
import logging
import multiprocessing
import os
import signal
import threading
import time
from concurrent.futures import Future, ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Callable, Iterator

log = logging.getLogger("breakaway.api")

#: Seconds :meth:`WorkerProcess.end` waits for its pool to release what it holds.
END_WAIT_S = 2.0

#: The signals a worker leaves to the server.
_SERVER_SIGNALS = {signal.SIGINT, signal.SIGTERM}


def _start_worker(parent: int, niceness: int) -> None:
    """Worker initializer, the first code that runs in a worker."""
    for sig in _SERVER_SIGNALS:
        signal.signal(sig, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _SERVER_SIGNALS)  # held while spawned
    if niceness:
        os.nice(niceness)

    def exit_with_parent() -> None:
        # killed without its shutdown running, the server cannot end this worker
        while os.getppid() == parent:
            time.sleep(1.0)
        os._exit(0)

    threading.Thread(target=exit_with_parent, name="exit-with-parent", daemon=True).start()


@contextlib.contextmanager
def _signals_held() -> Iterator[None]:
    """SIGINT and SIGTERM held (not lost) in this thread meanwhile, and in any process it
    spawns (the mask is inherited through fork and exec) until that process's
    initializer ignores them."""
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, _SERVER_SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


class WorkerProcess:
    """One worker process, started by the first :meth:`submit` after :meth:`end`.

    ``niceness``: added to the worker's scheduling niceness (batch work yields the CPU
    to the server's event loop)."""

    def __init__(self, niceness: int = 0) -> None:
        self.niceness = niceness
        self._pool: ProcessPoolExecutor | None = None
        self._lock = threading.Lock()  # guards _pool

    def submit(self, fn: Callable[..., Any], *args: Any) -> Future:
        """``fn(*args)`` in the worker (started now if there is none)."""
        with self._lock:
            if self._pool is None:
                # spawn, not fork: the server has threads, which a forked child would
                # inherit mid-lock. The pool's queues start multiprocessing's resource
                # tracker, which unblocks the signals when it is up: outside the hold
                self._pool = ProcessPoolExecutor(
                    max_workers=1, mp_context=multiprocessing.get_context("spawn"),
                    initializer=_start_worker, initargs=(os.getpid(), self.niceness))
            with _signals_held():  # the pool spawns its process within submit
                return self._pool.submit(fn, *args)

    def warm_up(self, fn: Callable[[], Any]) -> Future:
        """Start the worker now and run ``fn`` in it (its imports, compiled code), so
        that the first request does not wait for them; a failure is logged."""
        future = self.submit(fn)
        future.add_done_callback(_report_warm_up)
        return future

    def end(self) -> None:
        """End the worker now, if there is one: a running task is abandoned (its future
        fails with ``BrokenProcessPool``), a waiting one is cancelled, and the pool's
        pipes and semaphores are released before this returns."""
        with self._lock:
            pool, self._pool = self._pool, None
        if pool is None:
            return
        for process in list((pool._processes or {}).values()):
            process.kill()
        manager, results = pool._executor_manager_thread, pool._result_queue
        pool.shutdown(wait=False, cancel_futures=True)
        # the pool's management thread sees the process gone, fails the running future,
        # closes the call queue and reaps the process: some 30 ms; then the results' pipe
        # is closed here, as shutdown(wait=True) would. The wait is bounded: once, on a
        # loaded machine, that thread never woke, and a restart called from a request
        # held the server's event loop in this join for good
        if manager is None:
            return
        manager.join(END_WAIT_S)
        if manager.is_alive():
            log.warning("a worker pool did not end within %g s; left to end on its own",
                        END_WAIT_S)
        elif results is not None:
            results.close()


def _report_warm_up(future: Future) -> None:
    """A warm-up's outcome, read so that a failure is logged, not lost (a worker ended by a
    restart or the shutdown before it was warm is no failure)."""
    if future.cancelled() or isinstance(future.exception(), BrokenProcessPool):
        return
    if future.exception() is not None:
        log.error("a worker's warm-up failed", exc_info=future.exception())
