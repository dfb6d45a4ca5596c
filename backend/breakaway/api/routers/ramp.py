"""POST /api/ramp: the ramp experiment at one rate, as time series."""

from __future__ import annotations

from fastapi import APIRouter, HTTPException, Request
from fastapi.exceptions import RequestValidationError

from ...settings import get_settings
from ..errors import model_errors
from ..schemas import RampRequest, RampResponse
from ..simulation import RETRY_AFTER_S, ClientGone, SimulationTimeout, SimulatorBusy, run_ramp

router = APIRouter(prefix="/api", tags=["simulate"])


@router.post("/ramp", response_model=RampResponse,
             responses={422: {"description": "invalid parameters, or over the time budget"},
                        503: {"description": "the simulator stayed busy for the whole budget; "
                                             "retry after `Retry-After` seconds"}})
async def ramp(body: RampRequest, request: Request) -> RampResponse:
    """Simulate ``m·ẍ + F = k·t`` (``presliding``) or LuGre at one rate up to break-away.

    Returns u(t) = k·t, F(t), x(t), ẋ(t) and z(t) (at most 2000 samples), the
    break-away instant and the E13 value for the same parameters. Runs in the
    simulation worker within ``BREAKAWAY_SIMULATE_TIMEOUT_S``.
    """
    settings = get_settings()
    params = body.worker_params()
    try:
        with model_errors(RampRequest.model_fields.keys()):
            result = await request.app.state.simulations.run(
                settings.simulate_timeout_s, body.model, body.k, params,
                body.step_budget(), gone=request.is_disconnected, target=run_ramp)
    except (SimulatorBusy, ClientGone) as exc:
        # busy: others' runs held the worker for the whole budget; gone: nobody reads this
        raise HTTPException(status_code=503, detail="the simulator is busy; try again shortly",
                            headers={"Retry-After": str(RETRY_AFTER_S)}) from exc
    except SimulationTimeout as exc:
        raise RequestValidationError([{"type": "simulation_timeout", "loc": ("body", "k"),
                                       "msg": f"{exc}; ask for a larger rate"}]) from exc
    return RampResponse(model=body.model, k=body.k, params=params, **result)
