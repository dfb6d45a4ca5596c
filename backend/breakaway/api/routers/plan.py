"""POST /api/plan: what to measure next for a report or a set of parameters."""

from __future__ import annotations

from fastapi import APIRouter
from fastapi.exceptions import RequestValidationError

from ...plan import PlanError, plan_experiment
from ..plan_schemas import PlanRequest, PlanResponse

router = APIRouter(prefix="/api", tags=["plan"])


@router.post("/plan", response_model=PlanResponse,
             responses={422: {"description": "a bad field, or a report the plan cannot "
                                             "use (loc names the key)"}})
def plan(body: PlanRequest) -> PlanResponse:
    """The runs of one family, within the rig's limits, that determine what the data do
    not; the standard errors predicted before and after; the programme as CSV; and,
    where no run of the family can determine a target, why and which family would."""
    limits = body.limits.model_dump() if body.limits else None
    params = body.params.model_dump() if body.params else None
    ranges = {name: tuple(bounds) for name, bounds in body.ranges.items()} if body.ranges else None
    try:
        result = plan_experiment(body.family, report=body.report, params=params, limits=limits,
                                 runs=body.runs, noise=body.noise, targets=body.targets,
                                 ranges=ranges, grid=body.grid)
    except PlanError as err:
        raise RequestValidationError([{"type": "plan_error", "loc": ("body", *err.path),
                                       "msg": str(err)}]) from err
    return PlanResponse(**result)
