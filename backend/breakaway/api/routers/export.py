"""POST /api/export: the fitted model of a report as a download (what
``breakaway export`` writes): a Python module, a C99 file or JSON."""

from __future__ import annotations

from fastapi import APIRouter
from fastapi.exceptions import RequestValidationError
from fastapi.responses import Response

from ...export import LANGUAGES, ReportError, export_model
from ..export_schemas import EXPORT_MEDIA, ExportRequest

router = APIRouter(prefix="/api", tags=["fit"])


@router.post("/export", response_class=Response,
             responses={200: {"description": "the file, as an attachment",
                              "content": EXPORT_MEDIA},
                        422: {"description": "the report lacks what the export needs "
                                             "(loc names the key), or a bad field"}})
def export(body: ExportRequest) -> Response:
    """The data panel's downloads: the same text as ``breakaway export REPORT.json
    --lang LANG``, with a file name (``friction_model.py``, ``.c``, ``.json``)."""
    try:
        text = export_model(body.report, body.lang, s=body.s, t_0=body.t_0)
    except ReportError as err:
        raise RequestValidationError([{"type": "report_error",
                                       "loc": ("body", "report", *err.path),
                                       "msg": str(err)}]) from err
    filename, media_type = LANGUAGES[body.lang]
    return Response(text.encode("utf-8"), media_type=media_type,
                    headers={"Content-Disposition": f'attachment; filename="{filename}"'})
