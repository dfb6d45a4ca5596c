"""POST /api/explore: everything one redraw of the explorer needs."""

from __future__ import annotations

from fastapi import APIRouter

from ...frame import explore_frame
from ..encoding import FrameResponse
from ..errors import model_errors
from ..schemas import ExploreRequest, ExploreResponse

router = APIRouter(prefix="/api", tags=["explore"])


# the schema documents ExploreResponse; the frame goes out as FrameResponse (numpy
# arrays straight to JSON), which FastAPI sends as it is
@router.post("/explore", response_model=ExploreResponse, response_class=FrameResponse,
             responses={413: {"description": "the JSON body is over its size limit"}})
async def explore(request: ExploreRequest) -> FrameResponse:
    """Stribeck curve, hysteresis loop, phase family and break-away curves for one
    parameter set. ``async`` on purpose: the frame is ~1 ms of numpy, cheaper to run
    on the event loop than to hand to a thread."""
    with model_errors(ExploreRequest.model_fields.keys()):
        frame = explore_frame(request.params(), grid=request.grid.sizes() if request.grid else None)
    return FrameResponse(frame)
