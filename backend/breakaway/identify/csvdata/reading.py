"""Reading a measured-data file: bytes to lines, metadata and header, cells to
columns, and each column's values checked."""

from __future__ import annotations

import csv

import numpy as np

from ...params import MAGNITUDE

from .dataset import _EXPECTED, _BOM, ANGLES, KINDS, REQUIRED, DataError



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
    for kind in ("timeseries", "breakaway", "steady"):  # the documented priority
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


#: Units in a header cell that mark rotary data (as ``# units: rotary``).
_ROTARY_UNITS = {"rad", "rad/s", "n·m", "nm", "n*m", "n.m", "n m", "n·m/s", "nm/s", "n*m/s"}


def _strip_units(header):
    """Header names without a trailing unit (``F [N·m]``, ``x (rad)``), whether any of
    those units is rotary, and the angle x is in (``"deg"`` for ``x [deg]``, else None)."""
    names, rotary, angle = [], False, None
    for cell in header:
        name, unit = cell, ""
        for open_, close in (("[", "]"), ("(", ")")):
            if cell.endswith(close) and open_ in cell:
                name, unit = cell[: cell.rindex(open_)].strip(), cell[cell.rindex(open_) + 1:-1]
                break
        unit = unit.strip().lower()
        rotary |= unit in _ROTARY_UNITS or unit in ANGLES
        if name.strip().lower() == "x" and unit in ANGLES:
            angle = ANGLES[unit]
        names.append(name)
    return names, rotary, angle


# --------------------------------------------------------------------------- validation

#: Per-column value rules (the parameters' and the effects' ranges): (violation mask, what is required).
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
