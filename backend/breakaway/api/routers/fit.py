"""POST /api/fit and the fit jobs: upload a CSV (MODEL.md §6), get the §8 report."""

from __future__ import annotations

import orjson
from fastapi import APIRouter, File, Form, HTTPException, Request, UploadFile
from fastapi.concurrency import run_in_threadpool
from fastapi.responses import PlainTextResponse, Response

from ...identify import DataError, FitError, identify, parse_csv
from ...settings import get_settings
from ..errors import too_large, unprocessable
from ..fit_schemas import FitJobStatus, FitReport
from ..fitjobs import Busy

router = APIRouter(prefix="/api", tags=["fit"])

_KIND_HELP = "timeseries, steady or breakaway; default: a '# kind:' line or the columns"


def _data_error(err: DataError, field: str = "file") -> Response:
    detail = {"type": "data_error", "loc": ["body", field], "msg": str(err)}
    # line and column of the CSV are part of the message; also give them as fields
    body = {"detail": [{**detail, "line": err.line, "column": err.column}]}
    return Response(orjson.dumps(body), status_code=422, media_type="application/json")


class _TooLarge(Exception):
    """The uploaded file is over the upload limit (413, as the middleware answers)."""


async def _read_upload(file: UploadFile) -> bytes:
    limit = get_settings().max_upload_bytes
    data = await file.read(limit + 1)
    if len(data) > limit:
        raise _TooLarge
    return data


async def _parse(file: UploadFile, kind: str | None):
    data = await _read_upload(file)
    return await run_in_threadpool(parse_csv, data, kind or None,
                                   get_settings().max_upload_bytes)


@router.post("/fit", response_model=FitReport,
             responses={422: {"description": "bad CSV: the message names line and column"}})
async def fit(file: UploadFile = File(..., description="CSV file, MODEL.md §6"),
              kind: str | None = Form(None, description=_KIND_HELP)) -> FitReport | Response:
    """Fit the base model, trace the residual to missing effects, and report (§8).

    The work runs in a worker thread, so the server keeps answering meanwhile.
    """
    try:
        dataset = await _parse(file, kind)
        return FitReport(**await run_in_threadpool(identify, dataset))
    except _TooLarge:
        return too_large(get_settings().max_upload_bytes, upload=True)
    except DataError as err:
        return _data_error(err)
    except FitError as err:
        return unprocessable([{"type": "fit_error", "loc": ["body", "file"], "msg": str(err)}])


#: Seconds a client is asked to wait when every fit worker is busy (a short fit's time).
RETRY_AFTER_S = 2


@router.post("/fit/jobs", response_model=FitJobStatus, status_code=202)
async def start_fit(request: Request, file: UploadFile = File(...),
                    kind: str | None = Form(None, description=_KIND_HELP)) -> FitJobStatus | Response:
    """Start a fit in the background; poll ``GET /api/fit/jobs/{id}`` for progress."""
    if request.app.state.fit_jobs.full():
        # decided before the upload is parsed: a busy server does no work for it
        raise HTTPException(status_code=429, detail="every fit worker is busy; try again shortly",
                            headers={"Retry-After": str(RETRY_AFTER_S)})
    try:
        dataset = await _parse(file, kind)
    except _TooLarge:
        return too_large(get_settings().max_upload_bytes, upload=True)
    except DataError as err:
        return _data_error(err)
    try:
        job = request.app.state.fit_jobs.submit(dataset, file.filename or "upload.csv")
    except Busy as err:
        raise HTTPException(status_code=429, detail=str(err),
                            headers={"Retry-After": str(RETRY_AFTER_S)}) from None
    return _status(job)


def _status(job) -> FitJobStatus:
    return FitJobStatus(id=job.id, source=job.source, status=job.status, progress=job.progress,
                        message=job.message, error=job.error, report=job.report,
                        series=job.series)


def _job(job):
    """The job, or a 404 when there is none by that id."""
    if job is None:
        raise HTTPException(status_code=404, detail="no such fit job")
    return job


@router.get("/fit/jobs/{job_id}", response_model=FitJobStatus)
async def fit_status(job_id: str, request: Request) -> FitJobStatus | Response:
    return _status(_job(request.app.state.fit_jobs.get(job_id)))


@router.delete("/fit/jobs/{job_id}", response_model=FitJobStatus)
async def cancel_fit(job_id: str, request: Request) -> FitJobStatus | Response:
    return _status(_job(request.app.state.fit_jobs.cancel(job_id)))


@router.get("/fit/jobs/{job_id}/residuals.csv", response_class=PlainTextResponse)
async def fit_residuals(job_id: str, request: Request) -> Response:
    job = _job(request.app.state.fit_jobs.get(job_id))
    if job.residuals is None:
        raise HTTPException(status_code=404, detail="the fit job has no residuals (yet)")
    return PlainTextResponse(job.residuals, media_type="text/csv", headers={
        "content-disposition": 'attachment; filename="residuals.csv"'})
