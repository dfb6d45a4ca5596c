"""POST /api/simulate: break-away of the simulated ramp experiment."""

from __future__ import annotations

from fastapi import APIRouter, HTTPException, Request
from fastapi.exceptions import RequestValidationError

from ...settings import get_settings
from ..errors import model_errors
from ..schemas import SimulateRequest, SimulateResponse
from ..simulation import RETRY_AFTER_S, ClientGone, SimulationTimeout, SimulatorBusy

router = APIRouter(prefix="/api", tags=["simulate"])


@router.post("/simulate", response_model=SimulateResponse,
             responses={422: {"description": "invalid parameters, or over the time budget"},
                        503: {"description": "the simulator stayed busy for the whole budget; "
                                             "retry after `Retry-After` seconds"}})
async def simulate(body: SimulateRequest, request: Request) -> SimulateResponse:
    """Simulate ``m·ẍ + F = k·t`` (``presliding``, E7) or LuGre for each rate.

    Runs in the server's simulation worker process with a wall-clock budget
    (``BREAKAWAY_SIMULATE_TIMEOUT_S``); over it the answer is a 422. A rate that does
    not break away within ``BREAKAWAY_SIMULATE_MAX_STEPS`` steps reports ``null``.
    """
    settings = get_settings()
    params = body.lugre_params() if body.model == "lugre" else body.presliding_params()
    try:
        with model_errors(SimulateRequest.model_fields.keys()):
            result = await request.app.state.simulations.run(
                settings.simulate_timeout_s, body.model, body.k, params,
                body.step_budget(), gone=request.is_disconnected)
    except (SimulatorBusy, ClientGone) as exc:
        # busy: others' runs held the worker for the whole budget; gone: nobody reads this
        raise HTTPException(status_code=503, detail="the simulator is busy; try again shortly",
                            headers={"Retry-After": str(RETRY_AFTER_S)}) from exc
    except SimulationTimeout as exc:
        raise RequestValidationError([{"type": "simulation_timeout", "loc": ("body", "k"),
                                       "msg": f"{exc}; ask for fewer or larger rates"}]) from exc
    return SimulateResponse(model=body.model, params=params, **result)
