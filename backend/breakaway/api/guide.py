"""The documentation site under ``/guide/``: the static HTML that ``scripts/docs``
builds into ``docs/_build/html`` (``BREAKAWAY_DOCS_DIR``), served by the same process
as the explorer, so that it works with no network. ``/docs`` is the API's Swagger UI.

Sphinx's pages carry a few small inline scripts (the page's name for the search, the
theme's light/dark switch). The server's policy allows no inline script, so each page is
sent with a policy that allows exactly its own inline scripts, by their SHA-256 hashes.
Until the documentation is built, every ``/guide/`` path answers a short page that says
how to build it.
"""

from __future__ import annotations

import base64
import functools
import hashlib
import re
from pathlib import Path

from fastapi import FastAPI
from starlette.requests import Request
from starlette.responses import HTMLResponse, RedirectResponse, Response
from starlette.staticfiles import StaticFiles
from starlette.types import Receive, Scope, Send

from .middleware import CSP

#: Where the guide is served.
GUIDE_PATH = "/guide"

_NOT_BUILT = """<!doctype html>
<html lang="en">
<head><meta charset="utf-8"><title>Breakaway documentation: not built</title></head>
<body>
<h1>The documentation is not built yet</h1>
<p>Build it once in the checkout the server runs from, then reload this page:</p>
<pre>scripts/docs</pre>
<p>It writes the HTML to <code>docs/_build/html</code> (or set
<code>BREAKAWAY_DOCS_DIR</code> to a folder that holds it). Meanwhile the
<a href="/">explorer</a> and the <a href="/docs">HTTP API's interactive docs</a> work.</p>
</body>
</html>
"""

_INLINE_SCRIPT = re.compile(rb"<script(?![^>]*\bsrc=)[^>]*>(.*?)</script>", re.S)


@functools.lru_cache(maxsize=256)
def page_policy(path: str, mtime_ns: int) -> str:
    """The server's Content-Security-Policy with the page's inline scripts allowed by
    hash (cached per file version)."""
    body = Path(path).read_bytes()
    hashes = sorted({"'sha256-" + base64.b64encode(hashlib.sha256(script).digest()).decode() + "'"
                     for script in _INLINE_SCRIPT.findall(body)})
    return CSP.replace("script-src 'self'", " ".join(["script-src 'self'", *hashes]))


class GuideFiles(StaticFiles):
    """The built documentation, or a page saying how to build it."""

    def __init__(self, directory: Path) -> None:
        super().__init__(directory=directory, html=True, check_dir=False)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if not (Path(self.directory) / "index.html").is_file():
            await HTMLResponse(_NOT_BUILT, status_code=404)(scope, receive, send)
            return
        await super().__call__(scope, receive, send)

    def file_response(self, full_path, stat_result, scope, status_code=200) -> Response:
        response = super().file_response(full_path, stat_result, scope, status_code)
        if str(full_path).endswith(".html"):
            response.headers["content-security-policy"] = page_policy(
                str(full_path), stat_result.st_mtime_ns)
        return response


def mount_guide(app: FastAPI, directory: Path) -> None:
    """Serve ``directory`` under /guide/ (and /guide itself by a redirect there)."""

    async def to_index(request: Request) -> Response:
        return RedirectResponse(GUIDE_PATH + "/", status_code=307)

    app.router.add_route(GUIDE_PATH, to_index, include_in_schema=False, methods=["GET", "HEAD"])
    app.mount(GUIDE_PATH, GuideFiles(directory), name="guide")
