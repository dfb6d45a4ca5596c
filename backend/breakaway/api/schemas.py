"""Pydantic request and response models of the HTTP API (MODEL.md §9)."""

from __future__ import annotations

from pydantic import BaseModel


class Health(BaseModel):
    status: str
    version: str
