"""POST /api/loop: the position loop, as time series with its stick phases beside
(E13) and hunting."""

from __future__ import annotations

from fastapi import APIRouter, HTTPException, Request
from fastapi.exceptions import RequestValidationError

from ...settings import get_settings
from ..encoding import FrameResponse
from ..errors import model_errors
from ..loop_schemas import LoopRequest, LoopResponse
from ..simulation import RETRY_AFTER_S, ClientGone, SimulationTimeout, SimulatorBusy, run_loop

router = APIRouter(prefix="/api", tags=["simulate"])


# the schema documents LoopResponse; the run goes out as FrameResponse (numpy arrays
# straight to float32 JSON), which FastAPI sends as it is
@router.post("/loop", response_model=LoopResponse, response_class=FrameResponse,
             responses={422: {"description": "invalid parameters, or over the time budget"},
                        503: {"description": "the simulator stayed busy for the whole budget; "
                                             "retry after `Retry-After` seconds"}})
async def loop(body: LoopRequest, request: Request) -> FrameResponse:
    """Simulate ``m·ẍ + F = u`` under PID control (derivative on ṙ − ẋ, optional
    force limit, friction compensation c·Fss(ṙ)) for a step, ramp or sine reference.

    Returns the run on a uniform grid of ``points`` samples plus every break-away and
    stick-phase start, the stick phases with (E13) at their rate, hunting (or null) and
    the RMS error. Runs in the simulation worker within ``BREAKAWAY_SIMULATE_TIMEOUT_S``.
    """
    settings = get_settings()
    args = body.worker_args()
    try:
        with model_errors(LoopRequest.model_fields.keys()):
            result = await request.app.state.simulations.run(
                settings.simulate_timeout_s, args, gone=request.is_disconnected,
                target=run_loop)
    except (SimulatorBusy, ClientGone) as exc:
        # busy: others' runs held the worker for the whole budget; gone: nobody reads this
        raise HTTPException(status_code=503, detail="the simulator is busy; try again shortly",
                            headers={"Retry-After": str(RETRY_AFTER_S)}) from exc
    except SimulationTimeout as exc:
        raise RequestValidationError([{"type": "simulation_timeout", "loc": ("body", "duration"),
                                       "msg": f"{exc}; ask for a shorter run"}]) from exc
    used = {key: args[key] for key in ("model", "controller", "reference", "duration",
                                       "compensation", "F_hat")}
    return FrameResponse({**result, **used, "params": args["params"]})
