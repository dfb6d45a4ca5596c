"""The report's warnings, one module per rule.

Each rule reads a fit (or the data) and returns a list of entries made by
:func:`warning`; :mod:`breakaway.identify.diagnosis` gathers them in the report's order.
"""

from __future__ import annotations


def warning(code: str, parameter: str | None, message: str) -> dict:
    """One entry of the report's ``warnings``."""
    return {"code": code, "parameter": parameter, "message": message}


__all__ = ["warning"]
