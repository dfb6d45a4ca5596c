"""The server's worker processes (``api/processes.py``): ended whole, and never holding
the server that ends them."""

from __future__ import annotations

import logging
import os

import pytest

from breakaway.api import processes
from breakaway.api.processes import WorkerProcess


def _started() -> WorkerProcess:
    worker = WorkerProcess()
    assert worker.submit(os.getpid).result(timeout=120) != os.getpid()
    return worker


def test_ending_a_worker_kills_its_process_and_releases_its_pool(caplog):
    worker = _started()
    pool = worker._pool
    process = next(iter(pool._processes.values()))
    manager = pool._executor_manager_thread
    with caplog.at_level(logging.WARNING, logger="breakaway.api"):
        worker.end()
    assert not process.is_alive() and process.exitcode is not None
    assert not manager.is_alive()  # queues closed, process reaped before end returned
    assert "did not end" not in caplog.text
    assert worker._pool is None  # the next submit starts a new one


class _NeverEnding:
    """A pool's management thread that never ends (one was seen asleep for good, never
    woken, while a restart joined it from the server's event loop)."""

    def __init__(self):
        self.joined = []

    def join(self, timeout=None):
        self.joined.append(timeout)

    def is_alive(self):
        return True


def test_a_pool_that_never_ends_does_not_hold_the_server(caplog):
    worker = _started()
    pool = worker._pool
    process = next(iter(pool._processes.values()))
    real, stuck = pool._executor_manager_thread, _NeverEnding()
    pool._executor_manager_thread = stuck
    with caplog.at_level(logging.WARNING, logger="breakaway.api"):
        worker.end()
    assert stuck.joined == [processes.END_WAIT_S]  # a bounded wait, not join()
    assert "did not end within 2 s" in caplog.text
    real.join(30)
    assert not real.is_alive()  # the real thread ended on its own, and reaped the process
    # killed all the same (asked by its pid: the process object's own poll races the
    # pool's thread reaping it, and then reads "alive")
    with pytest.raises(ProcessLookupError):
        os.kill(process.pid, 0)
