"""Measured-data CSV files of the identification engine (MODEL.md §6).

A file is UTF-8 text, comma separated. Lines starting with ``#`` before the header carry
metadata as ``# key: value`` (a ``#`` line without ``:`` is a plain comment); the first
other non-blank line is the header naming the columns; every later non-blank line that
does not start with ``#`` is a data row. The kind of data is given explicitly, by a
``# kind: …`` metadata line, or detected from the columns:

============  ==================  =======================
kind          required columns    optional columns
============  ==================  =======================
timeseries    ``t, x, F``         ``v``
steady        ``v, F``            –
breakaway     ``k, F_ba``         ``dwell, direction``
============  ==================  =======================

Extra columns are ignored (and not validated). Every problem with the input raises
:class:`DataError`, whose message names the line (1-based, in the file as uploaded) and
the column; callers show ``str(err)`` and never a stack trace.

Speed: lines are filtered and cells counted in Python, the used columns are converted
by numpy's C parser; only when that fails does Python's ``float`` go through the cells to
find the offending one. NaN/Inf and range checks are vectorised. A 20 000-row file of
four columns parses in about 20 ms.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass, field

import numpy as np

from ..params import MAGNITUDE

__all__ = [
    "KINDS",
    "REQUIRED",
    "OPTIONAL",
    "MIN_ROWS",
    "DEFAULT_MAX_BYTES",
    "DataError",
    "Dataset",
    "parse_csv",
    "read_csv",
]

#: The kinds of measured data (MODEL.md §6).
KINDS = ("timeseries", "steady", "breakaway")
#: Required columns per kind, in the order of MODEL.md §6.
REQUIRED = {"timeseries": ("t", "x", "F"), "steady": ("v", "F"), "breakaway": ("k", "F_ba")}
#: Optional columns per kind that are read (and validated) when present.
OPTIONAL = {"timeseries": ("v",), "steady": (), "breakaway": ("dwell", "direction")}
#: Fewest data rows accepted.
MIN_ROWS = 10
#: Default upper limit on the size of a file [bytes] (20 MB, MODEL.md §6).
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
    """

    kind: str
    columns: dict[str, np.ndarray]
    meta: dict[str, str]
    n: int
    ignored_columns: tuple[str, ...]
    lines: np.ndarray
    meta_lines: dict[str, int] = field(default_factory=dict, repr=False)
    segments: tuple[int, ...] = ()

    @property
    def rotary(self) -> bool:
        """Rotary data: ``# units: rotary`` (or forces in N·m / positions in rad in the
        column headers, recorded by the parser as the same metadata)."""
        return self.meta.get("units", "").strip().lower() == "rotary"

    def unit(self, linear: str) -> str:
        """The unit of a quantity of these data given its linear unit (N → N·m, …)."""
        return _ROTARY_UNIT.get(linear, linear) if self.rotary else linear

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


def _fmt_size(nbytes: int) -> str:
    if nbytes >= 1024 * 1024 // 10:
        return f"{nbytes / (1024 * 1024):.1f} MB"
    if nbytes >= 1024:
        return f"{nbytes / 1024:.1f} kB"
    return f"{nbytes} bytes"


def _check_size(nbytes: int, max_bytes: int | None) -> None:
    if max_bytes is None or nbytes <= max_bytes:
        return
    size, limit = _fmt_size(nbytes), _fmt_size(max_bytes)
    if size == limit:  # e.g. 20.04 MB against 20.0 MB: rounding would hide the excess
        size, limit = f"{nbytes} bytes", f"{max_bytes} bytes"
    raise DataError(f"file is {size}; the limit is {limit}")


def _decode(data: bytes) -> str:
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
        offset = 3
    else:
        offset = 0
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        bad = data[exc.start : exc.start + 1].hex().upper()
        hint = "save the file as UTF-8 CSV"
        if data.startswith((b"\xff\xfe", b"\xfe\xff")):
            hint = "the file looks like UTF-16; save it as UTF-8 CSV"
        elif data.startswith(b"PK\x03\x04"):
            hint = "the file looks like a spreadsheet workbook; export it as UTF-8 CSV"
        raise DataError(
            f"not UTF-8 text (byte 0x{bad} at offset {exc.start + offset} cannot be decoded); "
            f"{hint}",
            line,
        ) from None


def _split(line: str) -> list[str]:
    """Cells of one (already stripped) line, each stripped; honours "quoted" cells."""
    if '"' in line:
        cells = next(csv.reader([line], skipinitialspace=True), [])
    else:
        cells = line.split(",")
    return [c.strip() for c in cells]


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _case_hints(header: list[str], names) -> list[str]:
    """``"'F' for 'f'"`` for each name missing from header but present in another case."""
    present = set(header)
    hints = []
    for name in names:
        if name in present:
            continue
        for h in header:
            if h.lower() == name.lower() and f"{name!r} for {h!r}" not in hints:
                hints.append(f"{name!r} for {h!r}")
    return hints


def _hint_text(hints: list[str]) -> str:
    return f" (did you mean {', '.join(hints)}?)" if hints else ""


def _normalise_kind(kind: str, line: int | None, source: str) -> str:
    k = str(kind).strip().lower()
    if k not in KINDS:
        raise DataError(f"unknown kind {str(kind).strip()!r}{source}: expected one of {', '.join(KINDS)}", line)
    return k


def _detect_kind(header: list[str], header_line: int) -> str:
    present = set(header)
    for kind in ("timeseries", "breakaway", "steady"):  # priority of MODEL.md §6 / the brief
        if set(REQUIRED[kind]) <= present:
            return kind
    names = [h for h in header if h]
    msg = f"unknown columns {', '.join(names) if names else '(none)'}: {_EXPECTED}"
    hints = _case_hints(header, [c for k in KINDS for c in REQUIRED[k]])
    msg += _hint_text(hints)
    if names and all(_is_number(h) for h in names):
        msg += "; the first line looks like data: the file needs a header line naming the columns"
    elif len(names) == 1 and (";" in names[0] or "\t" in names[0]):
        sep = "';'" if ";" in names[0] else "a tab"
        msg += f"; the header seems to use {sep} as separator, but the file must be comma separated"
    raise DataError(msg, header_line)


def _first_bad(masks: list[tuple[str, np.ndarray]]):
    """(row, column) of the earliest True over several boolean masks, or None."""
    best = None
    for name, mask in masks:
        if mask.any():
            row = int(np.argmax(mask))
            if best is None or row < best[0]:
                best = (row, name)
    return best


def _convert(rows, cells, used, index, n):
    """float64 columns ``used`` of the data rows, or (row, column) of the first bad cell.

    Fast path: numpy's C parser (:func:`numpy.loadtxt`) reads only the used columns. If it
    fails for any reason, Python's ``float`` decides, column by column; it is the
    authority on what a number is (it also accepts e.g. ``1_000`` that loadtxt refuses).
    """
    if cells is None:
        try:
            arr = np.loadtxt(rows, delimiter=",", usecols=[index[c] for c in used], ndmin=2,
                             comments=None, quotechar=None, dtype=np.float64)
            if arr.shape == (n, len(used)):
                return {c: np.ascontiguousarray(arr[:, j]) for j, c in enumerate(used)}
        except (ValueError, IndexError, TypeError):
            pass
        cells = [r.split(",") for r in rows]
    columns = {}
    bad = None
    for name in used:
        j = index[name]
        col = [row[j] for row in cells]
        try:
            columns[name] = np.fromiter(map(float, col), dtype=np.float64, count=n)
        except ValueError:
            for r, cell in enumerate(col):
                try:
                    float(cell)
                except ValueError:
                    if bad is None or r < bad[0]:
                        bad = (r, name)
                    break
    return bad if bad is not None else columns


# --------------------------------------------------------------------------- reading


def _read_lines(data, max_bytes):
    """The file's text lines, after the size and encoding checks."""
    if isinstance(data, (bytearray, memoryview)):
        data = bytes(data)
    if isinstance(data, bytes):
        _check_size(len(data), max_bytes)
        text = _decode(data)
    elif isinstance(data, str):
        # Each character takes 1 to 4 bytes in UTF-8: encode only when that is ambiguous.
        if max_bytes is not None and len(data) * 4 > max_bytes:
            _check_size(len(data.encode("utf-8", "surrogatepass")), max_bytes)
        text = data[1:] if data.startswith(_BOM) else data
    else:
        raise TypeError(f"data must be bytes or str, not {type(data).__name__}")

    if "\n" not in text and "\r" in text:  # classic Mac line endings
        lines = text.split("\r")
    else:
        lines = text.split("\n")  # a trailing "\r" is stripped with the other blanks

    return lines


def _read_meta_and_header(lines):
    """``# key: value`` metadata before the header, their lines, and the header's index."""
    meta: dict[str, str] = {}
    meta_lines: dict[str, int] = {}
    for i, raw in enumerate(lines):
        s = raw.strip()
        if not s or not s.strip(", \t"):
            continue
        if s[0] == "#":
            key, colon, value = s[1:].partition(":")
            key = key.strip().lower()
            if colon and key:
                meta[key] = value.strip()
                meta_lines[key] = i + 1
            continue
        return meta, meta_lines, i
    if any(line.lstrip().startswith("#") for line in lines):
        raise DataError("no header line: the file has only comment and metadata lines")
    raise DataError("the file is empty: expected a header line naming the columns")


#: Units in a header cell that mark rotary data (MODEL.md §6 ``# units: rotary``).
_ROTARY_UNITS = {"rad", "rad/s", "n·m", "nm", "n*m", "n.m", "n m", "n·m/s", "nm/s", "n*m/s"}


def _strip_units(header):
    """Header names without a trailing unit (``F [N·m]``, ``x (rad)``) and whether any
    of those units is rotary."""
    names, rotary = [], False
    for cell in header:
        name, unit = cell, ""
        for open_, close in (("[", "]"), ("(", ")")):
            if cell.endswith(close) and open_ in cell:
                name, unit = cell[: cell.rindex(open_)].strip(), cell[cell.rindex(open_) + 1:-1]
                break
        rotary |= unit.strip().lower() in _ROTARY_UNITS
        names.append(name)
    return names, rotary


# --------------------------------------------------------------------------- validation

#: Per-column value rules of MODEL.md §1, §6, §7: (violation mask, what is required).
_LOW, _HIGH = MAGNITUDE
_VALUE_RULES = {
    "k": (lambda a: ~((a >= _LOW) & (a <= _HIGH)),
          f"k, the actuation force rate, must be > 0 (between {_LOW:g} and {_HIGH:g})"),
    "F_ba": (lambda a: ~(a >= 0), "F_ba is a magnitude and must be >= 0"),
    "dwell": (lambda a: ~(a >= 0), "dwell, a time, must be >= 0"),
    "direction": (lambda a: ~((a == 1) | (a == -1)), "direction must be +1 or -1"),
}


def _validate_values(columns, cell_text, line_no) -> None:
    """The kinds' value constraints: each column's rule, and a strictly increasing t
    (a time series). Raises DataError at the first offending cell."""
    checks = [(c, _VALUE_RULES[c][0](columns[c])) for c in columns if c in _VALUE_RULES]
    violation = _first_bad(checks)
    if violation is not None:
        r, name = violation
        raise DataError(f"{_VALUE_RULES[name][1]}, got {cell_text(r, name)}",
                        int(line_no[r]), name)
    # a number past 1e30 overflows the model's terms: refused wherever it stands
    huge = _first_bad([(c, np.abs(columns[c]) > _HIGH) for c in columns])
    if huge is not None:
        r, name = huge
        raise DataError(f"{name} must lie within {_HIGH:g} in magnitude, got {cell_text(r, name)}",
                        int(line_no[r]), name)
    if "t" in columns and columns["t"].size > 1:
        step = np.diff(columns["t"]) <= 0
        if step.any():
            r = int(np.argmax(step)) + 1
            raise DataError(
                f"t must be strictly increasing, but t = {cell_text(r, 't')} does not exceed "
                f"t = {cell_text(r - 1, 't')} on line {line_no[r - 1]}",
                int(line_no[r]),
                "t",
            )


# --------------------------------------------------------------------------- parser


def parse_csv(data: bytes | str, kind: str | None = None, max_bytes: int = DEFAULT_MAX_BYTES) -> Dataset:
    """Parse and validate a measured-data CSV file (MODEL.md §6).

    Parameters
    ----------
    data : bytes or str
        The file's content. Bytes must be UTF-8 (a BOM is stripped); line endings may be
        ``\\n``, ``\\r\\n`` or ``\\r``.
    kind : str, optional
        ``"timeseries"``, ``"steady"`` or ``"breakaway"`` (case and surrounding blanks are
        ignored). Overrides a ``# kind:`` metadata line, which overrides detection from
        the columns (``t,x,F`` → timeseries, else ``k,F_ba`` → breakaway, else ``v,F`` →
        steady). ``None`` or an empty string means "not given".
    max_bytes : int, optional
        Size limit, checked before parsing (``None``: no limit).

    Returns
    -------
    Dataset

    Raises
    ------
    DataError
        For any problem with the input: size, encoding, missing/unknown/duplicate columns,
        wrong number of cells, non-numeric cells, NaN/Inf, values outside MODEL.md §1/§7
        (``k > 0``, ``F_ba >= 0``, ``dwell >= 0``, ``direction = ±1``), non-increasing
        ``t``, fewer than :data:`MIN_ROWS` rows. The message names line and column.
    """
    lines = _read_lines(data, max_bytes)

    # -- metadata and header
    meta, meta_lines, header_idx = _read_meta_and_header(lines)
    header_line = header_idx + 1
    header, rotary = _strip_units(_split(lines[header_idx].strip()))
    if rotary and "units" not in meta:
        meta["units"] = "rotary"  # N·m and rad in the header: label reports that way

    # -- kind
    if kind is not None and str(kind).strip():
        kind = _normalise_kind(kind, None, "")
        source = ""
    elif "kind" in meta:
        kind = _normalise_kind(meta["kind"], meta_lines["kind"], " in the '# kind:' metadata")
        source = f" (from the '# kind:' metadata on line {meta_lines['kind']})"
    else:
        kind = _detect_kind(header, header_line)
        source = ""

    required = REQUIRED[kind]
    wanted = required + OPTIONAL[kind]
    missing = [c for c in required if c not in header]
    if missing:
        names = ", ".join(repr(c) for c in missing)
        plural = "s" if len(missing) > 1 else ""
        shown = ", ".join(h for h in header if h) or "(none)"
        raise DataError(
            f"missing column{plural} {names} required for kind {kind!r}{source}; "
            f"the header has {shown}{_hint_text(_case_hints(header, missing))}",
            header_line,
            missing[0],
        )
    for name in wanted:
        positions = [j + 1 for j, h in enumerate(header) if h == name]
        if len(positions) > 1:
            raise DataError(
                f"duplicate column {name!r} (header positions {', '.join(map(str, positions))})",
                header_line,
                name,
            )
    used = [c for c in wanted if c in header]
    index = {c: header.index(c) for c in used}
    ignored = tuple(h for h in header if h and h not in used)

    # -- data rows
    body = [s.strip() for s in lines[header_idx + 1 :]]
    keep = [i for i, s in enumerate(body) if s and s[0] != "#" and s.strip(", \t")]
    rows = [body[i] for i in keep]
    line_no = np.asarray(keep, dtype=np.int64) + (header_idx + 2)
    n = len(rows)
    ncol = len(header)
    quoted = any('"' in row for row in rows)
    cells = [_split(r) for r in rows] if quoted else None

    counts = np.fromiter(map(len, cells) if quoted else (r.count(",") + 1 for r in rows),
                         dtype=np.int64, count=n)
    wrong = counts != ncol
    if wrong.any():
        r = int(np.argmax(wrong))
        raise DataError(
            f"{counts[r]} cell{'s' if counts[r] != 1 else ''}, expected {ncol} as in the "
            f"header on line {header_line}",
            int(line_no[r]),
        )

    def cell_text(r: int, name: str) -> str:
        row = cells[r] if cells is not None else rows[r].split(",")
        return row[index[name]].strip()

    columns = _convert(rows, cells, used, index, n) if n else {c: np.empty(0) for c in used}
    if isinstance(columns, tuple):  # (row, column) of the first cell that is not a number
        r, name = columns
        cell = cell_text(r, name)
        msg = "empty cell: a number is required" if not cell else f"{cell!r} is not a number"
        raise DataError(msg, int(line_no[r]), name)

    nonfinite = _first_bad([(c, ~np.isfinite(columns[c])) for c in used])
    if nonfinite is not None:
        r, name = nonfinite
        what = "NaN" if math.isnan(columns[name][r]) else "Inf"
        raise DataError(
            f"{cell_text(r, name)!r} is not a finite number ({what} is not allowed)",
            int(line_no[r]),
            name,
        )

    _validate_values(columns, cell_text, line_no)

    if n < MIN_ROWS:
        if n == 0:
            raise DataError(
                f"no data rows after the header on line {header_line}; "
                f"at least {MIN_ROWS} are required"
            )
        raise DataError(
            f"only {n} data row{'s' if n != 1 else ''} (lines {line_no[0]} to {line_no[-1]}); "
            f"at least {MIN_ROWS} are required"
        )

    dataset = Dataset(
        kind=kind,
        columns=columns,
        meta=meta,
        n=n,
        ignored_columns=ignored,
        lines=line_no,
        meta_lines=meta_lines,
    )
    _validate_meta(dataset)
    return dataset


def _validate_meta(dataset: Dataset) -> None:
    """The metadata the model reads (MODEL.md §6): ``# s:`` > 0 and ``# F0:`` finite,
    both within :data:`MAGNITUDE`; checked here so a bad file is refused on upload, not
    when its fit starts. Other keys (``source``, ``units``, …) are free text."""
    s = dataset.meta_float("s")
    if s is not None and not _LOW <= s <= _HIGH:
        raise DataError(f"metadata 's' (the presliding scale) must be > 0, between {_LOW:g} "
                        f"and {_HIGH:g}, got {dataset.meta['s']!r}", dataset.meta_lines.get("s"))
    F0 = dataset.meta_float("F0")
    if F0 is not None and abs(F0) > _HIGH:
        raise DataError(f"metadata 'F0' must lie within {_HIGH:g} in magnitude, got "
                        f"{dataset.meta['f0']!r}", dataset.meta_lines.get("f0"))


def read_csv(path, kind: str | None = None, max_bytes: int = DEFAULT_MAX_BYTES) -> Dataset:
    """Read and parse a measured-data CSV file; see :func:`parse_csv`.

    The size limit is checked on the file system before the file is read.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    kind : str, optional
        See :func:`parse_csv`.
    max_bytes : int, optional
        Size limit (``None``: no limit).

    Returns
    -------
    Dataset

    Raises
    ------
    DataError
        As :func:`parse_csv`, and when the file cannot be read (missing, a directory,
        no permission): ``"cannot read 'name': No such file or directory"``.
    """
    try:
        size = os.stat(path).st_size
        _check_size(size, max_bytes)
        with open(path, "rb") as fh:
            # Read at most one byte over the limit: a file growing after stat is caught too.
            data = fh.read() if max_bytes is None else fh.read(max_bytes + 1)
    except OSError as exc:
        reason = exc.strerror or exc.__class__.__name__
        raise DataError(f"cannot read {os.fspath(path)!r}: {reason}") from None
    return parse_csv(data, kind=kind, max_bytes=max_bytes)
