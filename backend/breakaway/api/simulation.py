"""Ramp simulations in a worker process, so a slow one never blocks the explorer.

The compiled integrator holds the GIL for the whole run, and a run with strong
velocity weakening at a small rate can chatter through thousands of reversals
(seconds). In a thread it would stall every other request of the server; in one worker
process the event loop stays free for ``/api/explore`` while the simulation runs, and
a run over the wall-clock budget is ended by ending the process.
"""

from __future__ import annotations

import asyncio
import logging
from concurrent.futures import Future
from concurrent.futures.process import BrokenProcessPool
from typing import Any, Awaitable, Callable

from .processes import WorkerProcess

log = logging.getLogger("breakaway.api")


class SimulationTimeout(Exception):
    """The simulation did not finish within its wall-clock budget."""


class SimulatorBusy(Exception):
    """The worker stayed busy with other runs for longer than the request's budget."""


class ClientGone(Exception):
    """The client left while its run went on; the run was ended."""


#: Seconds a client is asked to wait when the simulator is busy.
RETRY_AFTER_S = 2
#: Seconds between looks at a running simulation's client.
_POLL_S = 0.25
#: Seconds a run may go on after its client left before the worker is ended.
_GRACE_S = 0.5


def run_simulation(model: str, k: list[float], params: dict[str, float],
                   max_steps: int) -> dict[str, Any]:
    """Worker entry point: break-away of each rate for ``presliding`` or ``lugre``."""
    from ..dynamics import simulate_breakaway, simulate_lugre_breakaway

    if model == "lugre":
        result = simulate_lugre_breakaway(k, params, max_steps=max_steps)
    else:
        result = simulate_breakaway(k, max_steps=max_steps, **params)
    return {
        "k": result.k.tolist(),
        "u_ba": _nullable(result.u_ba),
        "F_ba": _nullable(result.F_ba),
        "t_ba": _nullable(result.t_ba),
        "reversals": [int(n) for n in result.reversals],
    }


def run_ramp(model: str, k: float, params: dict[str, float], max_steps: int) -> dict[str, Any]:
    """Worker entry point: one ramp run as time series (``POST /api/ramp``)."""
    from ..ramp import ramp_experiment

    return ramp_experiment(model, k, params, max_steps)


def run_loop(args: dict[str, Any]) -> dict[str, Any]:
    """Worker entry point: one run of the position loop (``POST /api/loop``),
    its time series as numpy arrays (sent as float32 JSON by the route)."""
    from ..loop import loop_experiment

    return loop_experiment(**args)


def _nullable(values) -> list[float | None]:
    return [float(v) if v == v and abs(v) != float("inf") else None for v in values]


def load_models() -> bool:
    """Load the compiled integrator and both loop models in the worker (numba's disk
    cache: ~0.3 s; the first request would otherwise pay it)."""
    from ..params import DEFAULTS, LOOP_DEFAULTS

    plant = {name: DEFAULTS[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "m")}
    run_simulation("presliding", [1.0], plant, 10_000)
    for model, plant in (("presliding", plant), ("lugre", {})):
        gains = {name: LOOP_DEFAULTS[model][name] for name in ("Kp", "Ki", "Kd", "u_max")}
        run_loop({"model": model, "params": {**plant, "z_ba": 0.95}, "controller": gains,
                  "reference": {"kind": "sine", "h": LOOP_DEFAULTS[model]["h"], "f": 1.0},
                  "duration": 0.01, "compensation": {"scale": 1.0}, "points": 10,
                  "max_steps": 10_000})
    return True


class SimulationRunner:
    """One worker process, started lazily (or at start-up), replaced after a timeout;
    at most ``queue`` requests wait for it (more are refused at once, 503)."""

    def __init__(self, queue: int = 16) -> None:
        self._worker = WorkerProcess()
        self._closed = False  # after shutdown no worker is started again
        self._turn: asyncio.Lock | None = None  # one run at a time (made on the loop)
        self._queue = queue
        self._waiting = 0

    def _submit(self, fn: Callable[..., Any], *args: Any) -> Future:
        if self._closed:
            raise SimulatorBusy("the server is shutting down")
        return self._worker.submit(fn, *args)

    def start(self) -> Future:
        """Take runs (again, after a shutdown: an app's lifespan may run more than once)
        and start the worker now, warmed up."""
        self._closed = False
        return self._worker.warm_up(load_models)

    async def run(self, timeout: float, *args: Any, target=run_simulation,
                  wait: float | None = None,
                  gone: Callable[[], Awaitable[bool]] | None = None) -> dict[str, Any]:
        """``target(*args)`` (by default :func:`run_simulation`) in the worker, one run
        at a time. Waiting for the worker is bounded by ``wait`` [s] (default
        ``timeout``; then :class:`SimulatorBusy`); the run has its own ``timeout`` [s],
        counted from its start.
        ``gone``: whether the client has left; a run it leaves behind is ended within a
        second (a short one is let finish: ending the worker costs a restart). A worker
        that died is replaced once."""
        if self._turn is None:
            self._turn = asyncio.Lock()
        if self._turn.locked() and self._waiting >= self._queue:
            raise SimulatorBusy(f"{self._waiting} simulations are already waiting")
        self._waiting += 1
        try:
            await asyncio.wait_for(self._turn.acquire(), timeout if wait is None else wait)
        except asyncio.TimeoutError:
            raise SimulatorBusy(f"the simulator stayed busy for "
                                f"{timeout if wait is None else wait:g} s") from None
        finally:
            self._waiting -= 1
        try:
            for attempt in (1, 2):
                try:
                    future = asyncio.wrap_future(self._submit(target, *args))
                    return await self._wait(future, timeout, gone)
                except BrokenProcessPool:
                    log.warning("simulation worker died (attempt %d); starting a new one",
                                attempt)
                    self._restart()
                    if attempt == 2:
                        raise
            raise AssertionError("unreachable")
        finally:
            self._turn.release()

    async def _wait(self, future: asyncio.Future, timeout: float, gone) -> dict[str, Any]:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout  # from the start of the run, not of the wait
        left_at = None
        try:
            while True:
                done, _ = await asyncio.wait({future}, timeout=_POLL_S)
                if done:
                    return future.result()
                now = loop.time()
                if now >= deadline:
                    self._restart()  # only this request's run is in the worker
                    raise SimulationTimeout(f"the simulation took longer than {timeout:g} s")
                if left_at is None and gone is not None and await gone():
                    left_at = now
                if left_at is not None and now - left_at >= _GRACE_S:
                    self._restart()
                    raise ClientGone
        finally:
            # a run left behind (timeout, client gone, this request cancelled) fails
            # with BrokenProcessPool once its worker is ended; nobody would read that,
            # and asyncio would log it as never retrieved: its result is renounced here
            future.cancel()

    def _restart(self) -> None:
        """End the worker that is stuck in a long run; the next request starts a new one."""
        self._worker.end()

    def shutdown(self) -> None:
        """End the worker now (it holds no state; a running simulation is abandoned) and
        start none again."""
        self._closed = True
        self._worker.end()

