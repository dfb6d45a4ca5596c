"""Pydantic model of ``POST /api/export`` (what ``breakaway export`` writes)."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, Field

from .schemas import _STRICT, Positive

#: What the route answers with, per language (the OpenAPI document lists them).
EXPORT_MEDIA = {"text/x-python": {"schema": {"type": "string"}},
                "text/x-c": {"schema": {"type": "string"}},
                "application/json": {"schema": {"type": "object"}}}


class ExportRequest(BaseModel):
    """An identification report (as ``POST /api/fit`` or ``breakaway fit --json`` gave it) and the
    language to export its fitted model in."""

    model_config = _STRICT

    report: dict[str, Any] = Field(description="the identification report, as POST /api/fit gave it")
    lang: Literal["python", "c", "json"] = Field(
        description="python: steady(v), class Presliding with step(x, t); c: bk_steady, "
                    "bk_state, bk_init, bk_step (C99, libm); json: parameters, effects, units")
    s: Positive | None = Field(None, description="presliding scale [1/m] where the report "
                               "has none (a steady fit) or to replace it")
    t_0: float | None = Field(None, description="the time [s] a drift refers to, where the "
                              "report has no t_0")
