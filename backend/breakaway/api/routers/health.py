"""GET /api/health."""

import os

from fastapi import APIRouter

from ... import __version__
from ..schemas import Health

router = APIRouter(prefix="/api", tags=["health"])


@router.get("/health", response_model=Health)
def health() -> Health:
    return Health(status="ok", version=__version__, worker=os.getpid())
