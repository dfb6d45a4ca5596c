"""GET /api/health."""

import os

from fastapi import APIRouter

from ... import __version__
from ..schemas import Health

router = APIRouter(prefix="/api", tags=["health"])


@router.get("/health", response_model=Health)
async def health() -> Health:
    """``async`` on purpose: answered on the event loop between two explorer frames, never
    queued behind the thread pool's work."""
    return Health(status="ok", version=__version__, worker=os.getpid())
