"""Pure ASGI middleware: security headers, request-body caps and a last-resort 422.

Pure ASGI (not ``BaseHTTPMiddleware``) because it adds only microseconds per request,
which matters next to a 1–2 ms explorer frame.
"""

from __future__ import annotations

import logging

from starlette.types import ASGIApp, Message, Receive, Scope, Send

from .errors import error_body, too_large_body

log = logging.getLogger("breakaway.api")

#: The policy of every page, the explorer and the API docs alike: scripts only from this
#: origin (no inline script, no eval); Plotly and Swagger UI set inline styles, and
#: Plotly exports PNG through data:/blob: URLs.
CSP = ("default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
       "img-src 'self' data: blob:; font-src 'self' data:; connect-src 'self'; "
       "object-src 'none'; base-uri 'none'; frame-ancestors 'none'; form-action 'self'")
_COMMON = [
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"no-referrer"),
    (b"x-frame-options", b"DENY"),
    (b"cross-origin-opener-policy", b"same-origin"),
    (b"cross-origin-resource-policy", b"same-origin"),
    (b"permissions-policy", b"camera=(), microphone=(), geolocation=()"),
]
_APP_HEADERS = [(b"content-security-policy", CSP.encode())] + _COMMON


class SecurityHeaders:
    """Adds the security headers to every HTTP response (no CORS headers at all)."""

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                # a response with a policy of its own (a documentation page allowing its
                # inline scripts by hash, api/guide.py) keeps it
                own = any(name.lower() == b"content-security-policy" for name, _ in headers)
                message["headers"] = headers + (_COMMON if own else _APP_HEADERS)
            await send(message)

        await self.app(scope, receive, send_with_headers)


class BodySizeLimit:
    """413 for a request body over the cap, decided before the body is buffered:
    ``json_limit`` for JSON and other bodies, ``upload_limit`` (the file's limit) for
    multipart uploads, which get ``framing`` bytes more for the multipart boundaries and
    form fields. Checks Content-Length and counts the bytes actually received (chunked
    bodies have no length). The answer names the file's limit, as /api/fit does for a
    file that fits the framing allowance but not the limit: one limit, one status."""

    def __init__(self, app: ASGIApp, json_limit: int, upload_limit: int,
                 framing: int = 64 * 1024) -> None:
        self.app = app
        self.json_limit = json_limit
        self.upload_limit = upload_limit
        self.framing = framing

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        headers = dict(scope.get("headers", []))
        content_type = headers.get(b"content-type", b"").lower()
        upload = content_type.startswith(b"multipart/")
        stated = self.upload_limit if upload else self.json_limit
        limit = stated + (self.framing if upload else 0)
        length = headers.get(b"content-length")
        if length is not None:
            try:
                too_large = int(length) > limit
            except ValueError:
                too_large = False
            if too_large:
                await _too_large(send, stated, upload)
                return
        received = 0
        rejected = False
        started = False

        async def counting_receive() -> Message:
            # over the cap mid-stream: answer 413 now and tell the app the client left
            nonlocal received, rejected
            if rejected:
                return {"type": "http.disconnect"}
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > limit:
                    rejected = True
                    if not started:
                        await _too_large(send, stated, upload)
                    return {"type": "http.disconnect"}
            return message

        async def guarded_send(message: Message) -> None:
            nonlocal started
            if rejected:  # after a 413 the app's own answer is dropped
                return
            if message["type"] == "http.response.start":
                started = True
            await send(message)

        await self.app(scope, counting_receive, guarded_send)


async def _too_large(send: Send, limit: int, upload: bool) -> None:
    body = too_large_body(limit, upload)
    await send({"type": "http.response.start", "status": 413,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode())]})
    await send({"type": "http.response.body", "body": body})


class CatchAll:
    """The last resort: an exception no handler took becomes a logged 422, never a 500.

    Validation and the model's ValueErrors are handled before this; reaching it means the
    model could not evaluate these inputs (e.g. an overflow at extreme values).
    """

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        started = False

        async def tracking_send(message: Message) -> None:
            nonlocal started
            if message["type"] == "http.response.start":
                started = True
            await send(message)

        try:
            await self.app(scope, receive, tracking_send)
        except Exception:  # noqa: BLE001 - this is the catch-all
            log.exception("unhandled error on %s %s", scope.get("method"), scope.get("path"))
            if started:
                return
            # the client learns what failed, never the exception's text (logged above)
            body = error_body([{"type": "unprocessable", "loc": ["body"],
                                "msg": "the model cannot evaluate these inputs; "
                                       "try values closer to the defaults"}])
            await send({"type": "http.response.start", "status": 422,
                        "headers": [(b"content-type", b"application/json"),
                                    (b"content-length", str(len(body)).encode())]})
            await send({"type": "http.response.body", "body": body})


class CompressPages:
    """gzip for the page's own files (HTML, CSS, ES modules) above 1 KB; API answers and
    the pre-compressed Plotly bundle pass untouched (an explorer frame is compact JSON
    whose compression would cost more than it saves on a local network)."""

    def __init__(self, app: ASGIApp) -> None:
        from starlette.middleware.gzip import GZipMiddleware

        self.app = app
        self.gzip = GZipMiddleware(app, minimum_size=1024, compresslevel=6)

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        path = scope.get("path", "") if scope["type"] == "http" else ""
        if scope["type"] != "http" or path.startswith(("/api/", "/vendor/plotly", "/openapi")):
            await self.app(scope, receive, send)
        else:
            await self.gzip(scope, receive, send)


class SameOrigin:
    """Answers only to allowed Host names, and refuses state-changing requests (POST,
    DELETE, …) that a browser sends from another origin (its ``Origin`` header names
    another host than the one asked, or is ``null``, as from a sandboxed frame of any
    site): no other site can start fits or simulations through a visitor's browser.
    Origins listed in ``BREAKAWAY_CORS_ORIGINS`` are let through (and get CORS headers
    from the app); the list is empty by default: CORS off."""

    SAFE = frozenset({"GET", "HEAD", "OPTIONS"})

    def __init__(self, app: ASGIApp) -> None:
        self.app = app

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        from urllib.parse import urlsplit

        from ..settings import get_settings

        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        host = headers.get("host", "")
        if not get_settings().host_allowed(host):
            await _refuse(send, 400, "host", f"this server does not answer to the host "
                          f"{host[:100]!r}; set BREAKAWAY_ALLOWED_HOSTS")
            return
        origin = headers.get("origin")
        if scope["method"] not in self.SAFE and origin \
                and urlsplit(origin).netloc.lower() != host.lower() \
                and origin not in get_settings().cors_origin_list():
            await _refuse(send, 403, "origin", "requests from another site's pages are "
                          "refused (the Origin header names another host)")
            return
        await self.app(scope, receive, send)


async def _refuse(send: Send, status: int, field: str, message: str) -> None:
    body = error_body([{"type": f"{field}_refused", "loc": ["header", field], "msg": message}])
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode())] + _APP_HEADERS})
    await send({"type": "http.response.body", "body": body})
