"""Files the frontend needs that are not in frontend/: Plotly and the API docs page.

``/vendor/plotly.min.js`` is Plotly's partial "basic" bundle vendored in
``frontend/vendor/`` (the explorer draws only scatter traces; see its README there) and
Swagger UI (5.x, which reads FastAPI's OpenAPI 3.1) comes from the installed
fastapi-offline package, so the explorer and the API docs work with no network. The docs
page starts Swagger UI from an external init script (the CSP allows no inline script).
"""

from __future__ import annotations

import functools
import gzip
import hashlib
from pathlib import Path

import fastapi_offline
from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse, RedirectResponse, Response

from breakaway.settings import get_settings

router = APIRouter(include_in_schema=False)

#: Plotly's partial bundle (scatter, bar, pie), vendored from the npm registry into the
#: frontend's vendor/ folder.
PLOTLY_BUNDLE = Path("vendor") / "plotly-basic-4.1.1.min.js"
SWAGGER_DIR = Path(fastapi_offline.__file__).resolve().parent / "static"
#: The Swagger UI files the docs page loads (served from the installed package).
SWAGGER_FILES = {"swagger-ui-bundle.js": "text/javascript", "swagger-ui.css": "text/css"}
_SWAGGER = "/vendor/swagger-ui"

_DOCS_HTML = f"""<!doctype html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>Breakaway API</title>
<link rel="stylesheet" href="{_SWAGGER}/swagger-ui.css">
</head>
<body>
<div id="swagger-ui"><p>Loading the interactive docs; the schema itself is at
<a href="/openapi.json">/openapi.json</a>.</p></div>
<script src="{_SWAGGER}/swagger-ui-bundle.js"></script>
<script src="/docs/init.js"></script>
</body>
</html>
"""

_DOCS_INIT = """window.ui = SwaggerUIBundle({
  url: "/openapi.json",
  dom_id: "#swagger-ui",
  presets: [SwaggerUIBundle.presets.apis],
  layout: "BaseLayout",
  deepLinking: true,
});
"""


@functools.cache
def _plotly_gzip(path: Path) -> tuple[bytes, str]:
    """Plotly compressed once per process (1.19 MB → 0.39 MB), and its ETag."""
    raw = path.read_bytes()
    return gzip.compress(raw, compresslevel=9, mtime=0), f'"{hashlib.sha256(raw).hexdigest()[:32]}"'


@router.get("/vendor/plotly.min.js")
def plotly_js(request: Request) -> Response:
    """Plotly's vendored bundle: gzip-compressed when the client accepts it,
    with an ETag and a long cache lifetime (it changes only with the vendored version)."""
    path = get_settings().frontend_dir / PLOTLY_BUNDLE
    body, etag = _plotly_gzip(path)
    headers = {"Cache-Control": "public, max-age=604800", "ETag": etag, "Vary": "Accept-Encoding"}
    if request.headers.get("if-none-match") == etag:
        return Response(status_code=304, headers=headers)
    if "gzip" in request.headers.get("accept-encoding", ""):
        return Response(body, media_type="text/javascript",
                        headers={**headers, "Content-Encoding": "gzip"})
    return FileResponse(path, media_type="text/javascript", headers=headers)


@router.get("/vendor/swagger-ui/{name}")
def swagger_asset(name: str) -> Response:
    if name not in SWAGGER_FILES:
        raise HTTPException(status_code=404, detail="not found")
    return FileResponse(SWAGGER_DIR / name, media_type=SWAGGER_FILES[name],
                        headers={"Cache-Control": "public, max-age=86400"})


@router.get("/docs")
def docs() -> HTMLResponse:
    return HTMLResponse(_DOCS_HTML)


@router.get("/docs/init.js")
def docs_init() -> Response:
    return Response(_DOCS_INIT, media_type="text/javascript")


@router.get("/favicon.ico")
def favicon() -> RedirectResponse:
    return RedirectResponse("/favicon.svg", status_code=301)
