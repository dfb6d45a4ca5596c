"""The parsed file (:class:`Dataset`), its kinds and columns, and :class:`DataError`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np



#: The kinds of measured data.
KINDS = ("timeseries", "steady", "breakaway")
#: Required columns per kind, in the documented order.
REQUIRED = {"timeseries": ("t", "x", "F"), "steady": ("v", "F"), "breakaway": ("k", "F_ba")}
#: Optional columns per kind that are read (and validated) when present.
OPTIONAL = {"timeseries": ("v",), "steady": (), "breakaway": ("dwell", "direction")}
#: Fewest data rows accepted.
MIN_ROWS = 10
#: Default upper limit on the size of a file [bytes] (20 MB).
DEFAULT_MAX_BYTES = 20 * 1024 * 1024

_EXPECTED = "expected t,x,F (timeseries), v,F (steady) or k,F_ba (breakaway)"
_BOM = "\ufeff"


def _shortened(text: str, limit: int) -> str:
    """``text`` cut in the middle to at most ``limit`` characters."""
    if len(text) <= limit:
        return text
    keep = limit - 1
    return text[: keep * 3 // 4] + "…" + text[len(text) - (keep - keep * 3 // 4):]


class DataError(ValueError):
    """Bad input: message names the line (1-based, in the file as uploaded) and the column.

    ``str(err)`` is a complete sentence: the message prefixed by ``"line N, column 'C': "``
    when both are known, ``"line N: "`` when only the line is, ``"column 'C': "`` when only
    the column is, nothing otherwise.

    Parameters
    ----------
    message : str
        What is wrong, without the line/column prefix.
    line : int, optional
        1-based line number in the file as uploaded.
    column : str, optional
        Name of the offending column, as written in the header.

    Attributes
    ----------
    message : str
        The message without prefix.
    line : int or None
    column : str or None
    """

    #: Longest message and column name kept: the message quotes the input (a cell, a
    #: header, a metadata value), and a 200 kB cell must not come back whole.
    MAX_MESSAGE = 400
    MAX_COLUMN = 60

    def __init__(self, message: str, line: int | None = None, column: str | None = None):
        message = _shortened(message, self.MAX_MESSAGE)
        column = None if column is None else _shortened(column, self.MAX_COLUMN)
        self.message = message
        self.line = line
        self.column = column
        if line is not None and column is not None:
            full = f"line {line}, column {column!r}: {message}"
        elif line is not None:
            full = f"line {line}: {message}"
        elif column is not None:
            full = f"column {column!r}: {message}"
        else:
            full = message
        super().__init__(full)

    def __reduce__(self):
        # Keep line and column through pickling (multiprocessing, caches).
        return (type(self), (self.message, self.line, self.column))


#: Linear units and their rotary counterparts.
_ROTARY_UNIT = {"N·s/m": "N·m·s/rad", "m/s": "rad/s", "1/m": "1/rad", "kg": "kg·m²",
                "N": "N·m", "m": "rad", "m/s²": "rad/s²", "N/s": "N·m/s",
                "N·(s/m)^n": "N·m·(s/rad)^n"}
#: Angles the header may give positions in (``x [deg]``); every unit with an angle in it
#: follows (V in deg/s, s in 1/deg, m_e in N·m·s²/deg).
ANGLES = {"rad": "rad", "deg": "deg", "degree": "deg", "degrees": "deg", "°": "deg"}


def unit_of(linear: str, rotary: bool, angle: str = "rad") -> str:
    """The unit of a quantity for linear or rotary data given its linear (SI) unit
    (N → N·m, m → rad, …), with positions in ``angle`` (``"rad"`` or ``"deg"``)."""
    if not rotary:
        return linear
    unit = _ROTARY_UNIT.get(linear, linear)
    if angle == "rad":
        return unit
    return "N·m·s²/deg" if unit == "kg·m²" else unit.replace("rad", angle)


@dataclass(frozen=True, eq=False)
class Dataset:
    """A parsed, validated measured-data file.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    columns : dict of str to numpy.ndarray
        float64 arrays of length ``n`` for the required columns of ``kind`` and those of
        its optional columns present in the file (required first, in the order of
        :data:`REQUIRED` then :data:`OPTIONAL`). All values are finite.
    meta : dict of str to str
        ``# key: value`` lines before the header; keys stripped and lower-cased (``# F0:``
        gives ``"f0"``), values stripped. A repeated key keeps its last value.
    n : int
        Number of data rows.
    ignored_columns : tuple of str
        Non-empty header names that were not read, in header order.
    lines : numpy.ndarray
        int64, the 1-based file line of each data row (for messages downstream).
    meta_lines : dict of str to int
        The 1-based file line of each ``meta`` key (for :meth:`meta_float` messages).
    segments : tuple of int
        Row indices where an independent record starts after the first (a time series
        screened in blocks); empty for a file.
    printed : dict of str to float
        The unit of the last digit each column was printed with (1e-7 for
        ``0.0000120``), read from the file's text; a column written in exponent notation
        has none. A position that sits on a grid coarser than its printed digits carries
        the grid as its own step (:func:`~breakaway.identify.kinematics.quantum`).
    weights : numpy.ndarray or None
        Each row's weight in a fit, the inverse of its prediction variance relative to
        the force's (set by the diagnosis where x's resolution makes some rows' force
        uncertain, :func:`~breakaway.identify.input_error.input_weights`); None, the parser's
        value: every row counts alike.
    """

    kind: str
    columns: dict[str, np.ndarray]
    meta: dict[str, str]
    n: int
    ignored_columns: tuple[str, ...]
    lines: np.ndarray
    meta_lines: dict[str, int] = field(default_factory=dict, repr=False)
    segments: tuple[int, ...] = ()
    printed: dict[str, float] = field(default_factory=dict, repr=False)
    weights: np.ndarray | None = field(default=None, repr=False)

    @property
    def rotary(self) -> bool:
        """Rotary data: ``# units: rotary`` (or forces in N·m / positions in rad in the
        column headers, recorded by the parser as the same metadata)."""
        return self.meta.get("units", "").strip().lower() == "rotary"

    @property
    def angle(self) -> str:
        """The angle rotary positions are in: ``"deg"`` when the header says so
        (``x [deg]``, recorded by the parser as ``# angle: deg``), else ``"rad"``."""
        return ANGLES.get(self.meta.get("angle", "rad").strip().lower(), "rad")

    def unit(self, linear: str) -> str:
        """The unit of a quantity of these data given its linear unit (N → N·m, …)."""
        return unit_of(linear, self.rotary, self.angle)

    def meta_float(self, key: str, default: float | None = None) -> float | None:
        """Numeric value of a metadata line.

        Parameters
        ----------
        key : str
            Metadata key, case-insensitive (``"F0"`` and ``"f0"`` are the same).
        default : float, optional
            Returned when the key is absent.

        Returns
        -------
        float or None
            The value, or ``default`` when the file has no such metadata line.

        Raises
        ------
        DataError
            The value is not a finite number; names the metadata line and the key.
        """
        key = key.strip().lower()
        if key not in self.meta:
            return default
        raw = self.meta[key]
        line = self.meta_lines.get(key)
        try:
            value = float(raw)
        except ValueError:
            raise DataError(f"metadata {key!r} must be a number, got {raw!r}", line) from None
        if not math.isfinite(value):
            what = "NaN" if math.isnan(value) else "Inf"
            raise DataError(
                f"metadata {key!r} must be a finite number, got {raw!r} ({what} is not allowed)",
                line,
            )
        return value


# --------------------------------------------------------------------------- helpers
