"""Fast, compact JSON for the explorer's arrays (orjson, numpy-native).

One frame holds ~9 000 floats. At full ``repr`` precision it is ~185 KB. Two compact
forms, both far below what a plot can show:

- float32 (the usual case): orjson writes the shortest repr that round-trips in float32,
  relative error <= 6e-8, ~94 KB, and the cast is nearly free;
- when a value lies outside float32's comfortable range (|x| > 1e30 or 0 < |x| < 1e-30,
  extreme but valid inputs) the float64 values are rounded to ``settings.payload_digits``
  significant digits instead (relative error <= 5e-7 for 7 digits; slower, but rare).

orjson serialises numpy arrays directly, ~20x faster than ``json.dumps`` of lists
(benchmarks/bench_explorer.py). Non-finite values become ``null``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import orjson
from fastapi.responses import JSONResponse

from ..settings import get_settings

#: Magnitudes sent as float32; outside them the rounded float64 path is taken.
FLOAT32_RANGE = (1e-30, 1e30)
_OPTIONS = orjson.OPT_SERIALIZE_NUMPY | orjson.OPT_NON_STR_KEYS


def round_significant(values: np.ndarray, digits: int) -> np.ndarray:
    """``values`` rounded to ``digits`` significant digits (non-finite ones unchanged).

    Through the decimal string, so the result prints with at most ``digits`` digits at
    any magnitude. Slow (~1 µs per value), which is fine: only extreme frames use it.
    """
    a = np.asarray(values, dtype=float)
    return np.array([float(f"{v:.{digits}g}") for v in a.tolist()], dtype=float)


def _arrays(obj: Any, out: list[np.ndarray]) -> list[np.ndarray]:
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind == "f":
            out.append(obj.ravel())
    elif isinstance(obj, dict):
        for value in obj.values():
            _arrays(value, out)
    elif isinstance(obj, (list, tuple)):
        for value in obj:
            _arrays(value, out)
    return out


def _map_arrays(obj: Any, convert) -> Any:
    if isinstance(obj, np.ndarray):
        return convert(obj) if obj.dtype.kind == "f" else obj
    if isinstance(obj, dict):
        return {key: _map_arrays(value, convert) for key, value in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_map_arrays(value, convert) for value in obj]
    return obj


def fits_float32(content: Any) -> bool:
    """True when every finite non-zero float of ``content`` lies inside FLOAT32_RANGE."""
    arrays = _arrays(content, [])
    if not arrays:
        return True
    magnitude = np.abs(np.concatenate(arrays))
    with np.errstate(invalid="ignore"):
        magnitude = magnitude[np.isfinite(magnitude) & (magnitude > 0)]
    return magnitude.size == 0 or (magnitude.min() >= FLOAT32_RANGE[0]
                                   and magnitude.max() <= FLOAT32_RANGE[1])


def dumps_frame(content: Any, digits: int | None = None) -> bytes:
    """JSON bytes of a dict of numpy arrays in the compact form (see the module doc)."""
    if fits_float32(content):
        return orjson.dumps(_map_arrays(content, lambda a: a.astype(np.float32)),
                            option=_OPTIONS)
    digits = get_settings().payload_digits if digits is None else digits
    return orjson.dumps(_map_arrays(content, lambda a: round_significant(a, digits)),
                        option=_OPTIONS)


class FrameResponse(JSONResponse):
    """A JSON response for numpy payloads (see :func:`dumps_frame`); a JSONResponse, so
    the OpenAPI document describes it with the route's response model."""

    def render(self, content: Any) -> bytes:
        return dumps_frame(content)
