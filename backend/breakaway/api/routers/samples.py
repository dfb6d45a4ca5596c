"""GET /api/samples: the data panel's bundled datasets (measured and "mystery")."""

from __future__ import annotations

from fastapi import APIRouter, HTTPException
from fastapi.concurrency import run_in_threadpool
from fastapi.responses import Response

from ...identify.samples import SAMPLES
from ..fit_schemas import SampleInfo

router = APIRouter(prefix="/api", tags=["samples"])


@router.get("/samples", response_model=list[SampleInfo])
def list_samples() -> list[SampleInfo]:
    return [SampleInfo(name=s.name, title=s.title, kind=s.kind, description=s.description,
                       quiz=s.quiz) for s in SAMPLES.values()]


@router.get("/samples/{name}.csv", response_class=Response,
            responses={200: {"content": {"text/csv": {}}}, 404: {"description": "no such sample"}})
async def sample_csv(name: str) -> Response:
    sample = SAMPLES.get(name)
    if sample is None:
        raise HTTPException(status_code=404, detail="no such sample")
    text = await run_in_threadpool(sample.csv)
    return Response(text, media_type="text/csv", headers={
        "content-disposition": f'attachment; filename="{name}.csv"'})
