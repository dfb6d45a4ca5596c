"""Measured-data CSV files of the identification engine.

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

The package: :mod:`.dataset` (the parsed file and the error), :mod:`.reading` (lines,
metadata, header, cells, values); here the two entry points.
"""

from __future__ import annotations

import math
import os

import numpy as np

from .dataset import DEFAULT_MAX_BYTES, KINDS, MIN_ROWS, OPTIONAL, REQUIRED, DataError, Dataset
from .reading import (_HIGH, _LOW, _case_hints, _check_size, _convert, _detect_kind, _first_bad,
                      _hint_text, _normalise_kind, _read_lines, _read_meta_and_header, _split,
                      _strip_units, _validate_values)

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




def parse_csv(data: bytes | str, kind: str | None = None, max_bytes: int = DEFAULT_MAX_BYTES) -> Dataset:
    """Parse and validate a measured-data CSV file.

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
        wrong number of cells, non-numeric cells, NaN/Inf, values outside the parameters' ranges
        (``k > 0``, ``F_ba >= 0``, ``dwell >= 0``, ``direction = ±1``), non-increasing
        ``t``, fewer than :data:`MIN_ROWS` rows. The message names line and column.
    """
    lines = _read_lines(data, max_bytes)

    # -- metadata and header
    meta, meta_lines, header_idx = _read_meta_and_header(lines)
    header_line = header_idx + 1
    header, rotary, angle = _strip_units(_split(lines[header_idx].strip()))
    if rotary and "units" not in meta:
        meta["units"] = "rotary"  # N·m and rad in the header: label reports that way
    if angle and "angle" not in meta:
        meta["angle"] = angle  # x [deg]: V, s and m_e are per degree

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
        printed=_printed_units(rows, cells, used, index),
    )
    _validate_meta(dataset)
    return dataset


#: Rows whose text is read for the digits each column was printed with.
PRINTED_SAMPLE = 2000


def _printed_units(rows, cells, used, index) -> dict[str, float]:
    """The unit of the last printed digit of each column (the most decimals over up to
    :data:`PRINTED_SAMPLE` rows spread over the file); none for a column with a value in
    exponent notation."""
    step = max(1, len(rows) // PRINTED_SAMPLE)
    sample = [cells[r] if cells is not None else rows[r].split(",")
              for r in range(0, len(rows), step)]
    units = {}
    for name in used:
        texts = [row[index[name]].strip() for row in sample]
        if not texts or any("e" in text or "E" in text for text in texts):
            continue
        decimals = max(len(text) - text.index(".") - 1 if "." in text else 0 for text in texts)
        units[name] = 10.0 ** -decimals
    return units


def _validate_meta(dataset: Dataset) -> None:
    """The metadata the model reads: ``# s:`` > 0 and ``# F0:`` finite,
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
