"""POST /api/fit and the fit jobs: upload a CSV, get the identification report."""

from __future__ import annotations

import orjson
from fastapi import APIRouter, File, Form, HTTPException, Request, UploadFile
from fastapi.responses import Response

from ...identify import DataError
from ...settings import get_settings
from ..errors import too_large, unprocessable
from ..fit_schemas import FitJobStatus, FitReport

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


async def _parse(request: Request, file: UploadFile, kind: str | None):
    data = await _read_upload(file)
    return await request.app.state.fit_workers.read(data, kind or None,
                                                    get_settings().max_upload_bytes)


#: Seconds a client is asked to wait when every fit worker and the queue are taken.
RETRY_AFTER_S = 5

_BUSY = {429: {"description": "every fit worker and the queue are taken; retry after "
                              "`Retry-After` seconds (decided before the upload is read)"},
         413: {"description": "the file is over the upload limit"},
         422: {"description": "bad CSV: the message names line and column"}}


def _refuse_when_full(request: Request) -> None:
    if request.app.state.fit_workers.full():
        # decided before the upload is read: a busy server does no work for it
        raise HTTPException(status_code=429, detail="every fit worker is busy; try again shortly",
                            headers={"Retry-After": str(RETRY_AFTER_S)})


def _create(request: Request, file: UploadFile) -> str:
    job_id = request.app.state.fit_workers.create(file.filename or "upload.csv")
    if job_id is None:  # another request took the last place while this one was read
        raise HTTPException(status_code=429, detail="every fit worker is busy; try again shortly",
                            headers={"Retry-After": str(RETRY_AFTER_S)})
    return job_id


@router.post("/fit", response_model=FitReport, responses=_BUSY)
async def fit(request: Request,
              file: UploadFile = File(..., description="CSV file: timeseries t,x,F; steady v,F; breakaway k,F_ba"),
              kind: str | None = Form(None, description=_KIND_HELP)) -> FitReport | Response:
    """Fit the base model, trace the residual to missing effects, and report.

    For small files and scripts: the fit runs in a fit worker process under the same
    limits as a job, and is stopped when the client goes away.
    """
    _refuse_when_full(request)
    try:
        dataset = await _parse(request, file, kind)
    except _TooLarge:
        return too_large(get_settings().max_upload_bytes, upload=True)
    except DataError as err:
        return _data_error(err)
    workers = request.app.state.fit_workers
    job_id = _create(request, file)
    await workers.run(job_id, dataset, gone=request.is_disconnected)
    job = workers.store.get(job_id)
    if job["status"] == "done":
        return FitReport(**job["report"])
    return unprocessable([{"type": "fit_error", "loc": ["body", "file"],
                           "msg": job["error"] or "the fit was cancelled"}])


@router.post("/fit/jobs", response_model=FitJobStatus, status_code=202, responses=_BUSY)
async def start_fit(request: Request, file: UploadFile = File(...),
                    kind: str | None = Form(None, description=_KIND_HELP)) -> FitJobStatus | Response:
    """Start a fit in the background; poll ``GET /api/fit/jobs/{id}`` for progress."""
    _refuse_when_full(request)
    try:
        dataset = await _parse(request, file, kind)
    except _TooLarge:
        return too_large(get_settings().max_upload_bytes, upload=True)
    except DataError as err:
        return _data_error(err)
    workers = request.app.state.fit_workers
    job_id = _create(request, file)
    workers.start(job_id, dataset)
    return _status(workers.store.get(job_id))


def _status(job: dict) -> FitJobStatus:
    return FitJobStatus(id=job["id"], source=job["source"], status=job["status"],
                        progress=job["progress"], message=job["message"], error=job["error"],
                        report=job["report"], series=job["series"])


def _job(request: Request, job_id: str) -> dict:
    """The job, or a 404 when there is none by that id."""
    job = request.app.state.fit_workers.store.get(job_id)
    if job is None:
        raise HTTPException(status_code=404, detail="no such fit job")
    return job


_MISSING = {404: {"description": "no such fit job"}}


@router.get("/fit/jobs/{job_id}", response_model=FitJobStatus, responses=_MISSING)
async def fit_status(job_id: str, request: Request) -> FitJobStatus:
    return _status(_job(request, job_id))


@router.delete("/fit/jobs/{job_id}", response_model=FitJobStatus, responses=_MISSING)
async def cancel_fit(job_id: str, request: Request) -> FitJobStatus:
    """Cancel a queued or running fit: it stops within a second; a finished one is left."""
    request.app.state.fit_workers.cancel(job_id)
    return _status(_job(request, job_id))


@router.get("/fit/jobs/{job_id}/residuals.csv", response_class=Response,
            responses={200: {"content": {"text/csv": {}}},
                       404: {"description": "no such job, or no residuals yet"}})
async def fit_residuals(job_id: str, request: Request) -> Response:
    job = _job(request, job_id)
    if job["residuals"] is None:
        raise HTTPException(status_code=404, detail="the fit job has no residuals (yet)")
    return Response(job["residuals"], media_type="text/csv", headers={
        "content-disposition": 'attachment; filename="residuals.csv"'})
