"""Tests of the measured-data CSV parser (MODEL.md §6), inputs generated in code."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from breakaway.identify.csvdata import (
    DEFAULT_MAX_BYTES,
    KINDS,
    MIN_ROWS,
    OPTIONAL,
    REQUIRED,
    DataError,
    Dataset,
    parse_csv,
    read_csv,
)

# ----------------------------------------------------------------------------- helpers


def columns_for(kind: str, n: int = 20, optional: bool = True) -> dict[str, np.ndarray]:
    """Plausible, valid columns of a kind (every value exactly representable by repr)."""
    i = np.arange(n, dtype=float)
    if kind == "timeseries":
        cols = {
            "t": 1e-3 * i,
            "x": 1e-4 * np.sin(0.3 * i),
            "F": 1.2 * np.tanh(np.cos(0.3 * i)) + 1e-3 * np.sin(7.0 * i),
        }
        if optional:
            cols["v"] = 0.03 * np.cos(0.3 * i)
    elif kind == "steady":
        cols = {"v": np.linspace(-0.5, 0.5, n), "F": np.tanh(np.linspace(-5.0, 5.0, n))}
    elif kind == "breakaway":
        cols = {"k": 0.01 + 2.0 * i, "F_ba": 1.5 - 0.4 * (1 - np.exp(-i / 5))}
        if optional:
            cols["dwell"] = 0.5 * (i % 3)
            cols["direction"] = np.where(i % 2 == 0, 1.0, -1.0)
    else:
        raise AssertionError(kind)
    return cols


def make_csv(
    cols: dict[str, np.ndarray | list],
    meta: dict[str, str] | None = None,
    comments: tuple[str, ...] = (),
    newline: str = "\n",
) -> str:
    """CSV text: comment lines, '# key: value' lines, a header and one row per sample."""
    out = [f"# {c}" for c in comments]
    out += [f"# {k}: {v}" for k, v in (meta or {}).items()]
    names = list(cols)
    out.append(",".join(names))
    n = len(next(iter(cols.values())))
    for r in range(n):
        out.append(",".join(_cell(cols[c][r]) for c in names))
    return newline.join(out) + newline


def _cell(value) -> str:
    return value if isinstance(value, str) else repr(float(value))


def with_cell(cols: dict, column: str, row: int, text: str) -> dict:
    """Copy of cols (as lists of str) with one cell replaced by raw text."""
    out = {c: [_cell(v) for v in vals] for c, vals in cols.items()}
    out[column][row] = text
    return out


def raises(text, match: str, line, column, **kw) -> DataError:
    """Parse, expect a DataError matching ``match`` with the given line and column."""
    with pytest.raises(DataError, match=match) as info:
        parse_csv(text, **kw)
    err = info.value
    assert err.line == line, str(err)
    assert err.column == column, str(err)
    assert "Traceback" not in str(err)
    return err


HEADER_LINE = 1  # make_csv without metadata: header on line 1, data row r on line r + 2


# ----------------------------------------------------------------------------- DataError


@pytest.mark.parametrize(
    "line, column, expected",
    [
        (14, "F", "line 14, column 'F': 'abc' is not a number"),
        (14, None, "line 14: 'abc' is not a number"),
        (None, "F", "column 'F': 'abc' is not a number"),
        (None, None, "'abc' is not a number"),
    ],
)
def test_data_error_message_prefix(line, column, expected):
    err = DataError("'abc' is not a number", line, column)
    assert str(err) == expected
    assert isinstance(err, ValueError)
    assert (err.line, err.column, err.message) == (line, column, "'abc' is not a number")
    copy = pickle.loads(pickle.dumps(err))
    assert (str(copy), copy.line, copy.column) == (expected, line, column)


def test_constants():
    assert KINDS == ("timeseries", "steady", "breakaway")
    assert REQUIRED == {"timeseries": ("t", "x", "F"), "steady": ("v", "F"), "breakaway": ("k", "F_ba")}
    assert OPTIONAL == {"timeseries": ("v",), "steady": (), "breakaway": ("dwell", "direction")}
    assert MIN_ROWS == 10
    assert DEFAULT_MAX_BYTES == 20 * 1024 * 1024


# ----------------------------------------------------------------------------- round trip


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("optional", [True, False])
@pytest.mark.parametrize("as_bytes", [True, False])
def test_round_trip(kind, optional, as_bytes):
    cols = columns_for(kind, n=25, optional=optional)
    text = make_csv(cols)
    ds = parse_csv(text.encode("utf-8") if as_bytes else text)
    assert isinstance(ds, Dataset)
    assert ds.kind == kind
    assert ds.n == 25
    assert list(ds.columns) == list(cols)
    for name, values in cols.items():
        got = ds.columns[name]
        assert got.dtype == np.float64 and got.shape == (25,)
        np.testing.assert_allclose(got, values, rtol=0, atol=1e-12)
    assert ds.ignored_columns == ()
    assert ds.meta == {}
    assert ds.lines.dtype.kind == "i"
    np.testing.assert_array_equal(ds.lines, np.arange(25) + 2)


def test_columns_in_any_order_and_whitespace():
    cols = columns_for("timeseries", n=12)
    reordered = {"F": cols["F"], "v": cols["v"], "t": cols["t"], "x": cols["x"]}
    text = make_csv(reordered).replace(",", " ,  ").replace("\n", "  \n")
    ds = parse_csv(text)
    assert list(ds.columns) == ["t", "x", "F", "v"]
    for name in cols:
        np.testing.assert_allclose(ds.columns[name], cols[name], rtol=0, atol=1e-12)


def test_blank_and_comment_lines_keep_file_line_numbers():
    cols = columns_for("steady", n=12)
    lines = make_csv(cols, meta={"source": "bench"}, comments=("a comment",)).splitlines()
    # lines: 1 comment, 2 meta, 3 header, 4.. data; insert blanks and comments after the header
    lines.insert(3, "")
    lines.insert(6, "# a note in the middle")
    lines.insert(8, "   ")
    lines.insert(9, ",,")
    ds = parse_csv("\n".join(lines) + "\n\n")
    assert ds.n == 12
    expected = [i + 1 for i, s in enumerate(lines) if i > 2 and s.strip(", ") and not s.startswith("#")]
    np.testing.assert_array_equal(ds.lines, expected)
    assert ds.lines[0] == 5


def test_quoted_cells():
    cols = columns_for("steady", n=12)
    text = make_csv({**cols, "note": ["plain"] * 12})
    lines = text.splitlines()
    lines[0] = '"v","F","note"'
    lines[3] = lines[3].replace("plain", '"with, comma"')
    ds = parse_csv("\n".join(lines))
    assert ds.kind == "steady" and ds.n == 12
    assert ds.ignored_columns == ("note",)
    np.testing.assert_allclose(ds.columns["F"], cols["F"], rtol=0, atol=1e-12)


# ----------------------------------------------------------------------------- kind


@pytest.mark.parametrize(
    "names, kind",
    [
        (("t", "x", "F"), "timeseries"),
        (("t", "x", "F", "v"), "timeseries"),  # {v, F} present too: timeseries wins
        (("v", "F"), "steady"),
        (("k", "F_ba"), "breakaway"),
        (("k", "F_ba", "v", "F"), "breakaway"),  # breakaway before steady
        (("t", "x", "F", "k", "F_ba"), "timeseries"),
    ],
)
def test_kind_detected_from_columns(names, kind):
    n = 12
    source = {**columns_for("timeseries", n), **columns_for("breakaway", n)}
    cols = {c: source[c] for c in names}
    ds = parse_csv(make_csv(cols))
    assert ds.kind == kind
    used = REQUIRED[kind] + OPTIONAL[kind]
    assert set(ds.columns) == {c for c in names if c in used}
    assert ds.ignored_columns == tuple(c for c in names if c not in used)


@pytest.mark.parametrize("meta_kind, expected", [("steady", "steady"), ("  Steady ", "steady")])
def test_kind_from_metadata(meta_kind, expected):
    # t, x, F, v would be detected as timeseries; the metadata line says steady
    cols = columns_for("timeseries", n=12)
    ds = parse_csv(make_csv(cols, meta={"kind": meta_kind}))
    assert ds.kind == expected
    assert list(ds.columns) == ["v", "F"]
    assert ds.ignored_columns == ("t", "x")
    assert ds.meta["kind"] == meta_kind.strip()


@pytest.mark.parametrize("meta", [None, {"kind": "timeseries"}, {"kind": "nonsense"}])
def test_explicit_kind_overrides_metadata_and_detection(meta):
    cols = columns_for("timeseries", n=12)
    ds = parse_csv(make_csv(cols, meta=meta), kind="steady")
    assert ds.kind == "steady"
    assert list(ds.columns) == ["v", "F"]


@pytest.mark.parametrize("kind", [None, ""])
def test_empty_explicit_kind_means_not_given(kind):
    ds = parse_csv(make_csv(columns_for("breakaway", 12)), kind=kind)
    assert ds.kind == "breakaway"


def test_unknown_explicit_kind():
    text = make_csv(columns_for("steady", 12))
    raises(text, r"unknown kind 'ramp': expected one of timeseries, steady, breakaway", None, None,
           kind="ramp")


def test_unknown_metadata_kind():
    text = make_csv(columns_for("steady", 12), meta={"source": "x", "kind": "ramp"})
    raises(text, r"unknown kind 'ramp'.*expected one of timeseries, steady, breakaway", 2, None)


@pytest.mark.parametrize("source", ["explicit", "metadata"])
def test_missing_column_for_given_kind(source):
    cols = columns_for("steady", 12)
    if source == "explicit":
        err = raises(make_csv(cols), r"missing columns 'k', 'F_ba' required for kind 'breakaway'",
                     HEADER_LINE, "k", kind="breakaway")
    else:
        err = raises(make_csv(cols, meta={"kind": "breakaway"}),
                     r"missing columns 'k', 'F_ba' required for kind 'breakaway' \(from the "
                     r"'# kind:' metadata on line 1\)", 2, "k")
    assert "the header has v, F" in str(err)


# ----------------------------------------------------------------------------- metadata


def test_metadata_parsing():
    cols = columns_for("timeseries", 12)
    text = make_csv(
        cols,
        meta={"S": " 1000 ", "F0": "-0.25", "Source": "bench: run 3, 2024", "empty": ""},
        comments=("plain comment without colon",),
    )
    text = "\n" + text.replace("# F0:", "#F0 :")  # leading blank line, no space after '#'
    ds = parse_csv(text)
    assert ds.meta == {"s": "1000", "f0": "-0.25", "source": "bench: run 3, 2024", "empty": ""}
    assert ds.meta_float("s") == 1000.0
    assert ds.meta_float("F0") == -0.25
    assert ds.meta_float("f0", 3.0) == -0.25
    assert ds.meta_float("missing") is None
    assert ds.meta_float("missing", 1.0) == 1.0
    assert ds.n == 12 and ds.lines[0] == 8


@pytest.mark.parametrize(
    "value, match",
    [
        ("abc", r"metadata 's' must be a number, got 'abc'"),
        ("1000 1/m", r"metadata 's' must be a number, got '1000 1/m'"),
        ("", r"metadata 's' must be a number, got ''"),
        ("nan", r"metadata 's' must be a finite number, got 'nan' \(NaN is not allowed\)"),
        ("-inf", r"metadata 's' must be a finite number, got '-inf' \(Inf is not allowed\)"),
    ],
)
def test_bad_metadata_number(value, match):
    # the model reads s: a bad one is refused when the file is read, not when a fit starts
    with pytest.raises(DataError, match=match) as info:
        parse_csv(make_csv(columns_for("breakaway", 12), meta={"source": "x", "s": value}))
    assert info.value.line == 2
    assert info.value.column is None
    assert str(info.value).startswith("line 2: ")


@pytest.mark.parametrize("key, value, match", [
    ("s", "-1", r"metadata 's' \(the presliding scale\) must be > 0, between 1e-30 and 1e\+30, got '-1'"),
    ("s", "5e-324", r"metadata 's' .* got '5e-324'"),
    ("F0", "1e308", r"metadata 'F0' must lie within 1e\+30 in magnitude, got '1e308'"),
])
def test_metadata_the_model_reads_is_checked_on_reading(key, value, match):
    with pytest.raises(DataError, match=match) as info:
        parse_csv(make_csv(columns_for("breakaway", 12), meta={key: value}))
    assert info.value.line == 1  # the metadata line, the file's first


def test_free_text_metadata_is_not_checked():
    ds = parse_csv(make_csv(columns_for("breakaway", 12), meta={"source": "bench 3", "sigma": "-2"}))
    assert ds.meta["sigma"] == "-2"


def test_hash_lines_after_header_are_not_metadata():
    lines = make_csv(columns_for("steady", 12)).splitlines()
    lines.insert(1, "# s: 5")
    ds = parse_csv("\n".join(lines))
    assert ds.meta == {} and ds.n == 12


# ----------------------------------------------------------------------------- extras, encodings


def test_extra_columns_ignored_and_not_validated():
    cols = columns_for("steady", 12)
    extra = {"temperature": ["abc"] * 12, "F": cols["F"], "t": ["nan"] * 12, "v": cols["v"],
             "": [""] * 12}
    extra["t"][3] = "-inf"
    ds = parse_csv(make_csv(extra))
    assert ds.kind == "steady"
    assert list(ds.columns) == ["v", "F"]
    assert ds.ignored_columns == ("temperature", "t")
    np.testing.assert_allclose(ds.columns["F"], cols["F"], rtol=0, atol=1e-12)


def test_unused_duplicate_extra_column_is_not_an_error():
    cols = columns_for("steady", 12)
    text = make_csv(cols).replace("v,F", "v,F,note,note", 1)
    text = "\n".join(line + ",a,b" if i else line for i, line in enumerate(text.splitlines()))
    ds = parse_csv(text)
    assert ds.ignored_columns == ("note", "note")


@pytest.mark.parametrize("bom", [True, False])
@pytest.mark.parametrize("newline", ["\r\n", "\n", "\r"])
def test_line_endings_and_bom(bom, newline):
    cols = columns_for("timeseries", 15)
    text = make_csv(cols, meta={"s": "2"}, newline=newline)
    data = (b"\xef\xbb\xbf" if bom else b"") + text.encode("utf-8")
    ds = parse_csv(data)
    assert ds.kind == "timeseries" and ds.n == 15
    assert ds.meta == {"s": "2"}
    np.testing.assert_allclose(ds.columns["F"], cols["F"], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(ds.lines, np.arange(15) + 3)
    assert parse_csv(("\ufeff" if bom else "") + text).n == 15


def test_bom_then_error_keeps_line_numbers():
    cols = with_cell(columns_for("steady", 12), "F", 4, "oops")
    data = b"\xef\xbb\xbf" + make_csv(cols, newline="\r\n").encode()
    with pytest.raises(DataError, match=r"line 6, column 'F': 'oops' is not a number") as info:
        parse_csv(data)
    assert (info.value.line, info.value.column) == (6, "F")


def test_utf8_text_in_metadata():
    ds = parse_csv(make_csv(columns_for("steady", 12), meta={"operator": "Jürgen Müller, δ-test"}).encode())
    assert ds.meta["operator"] == "Jürgen Müller, δ-test"


@pytest.mark.parametrize("prefix", [b"", b"\xef\xbb\xbf"])
@pytest.mark.parametrize("where, line", [("meta", 2), ("data", 6)])
def test_not_utf8(prefix, where, line):
    text = make_csv(columns_for("steady", 12), meta={"a": "1", "b": "2"})
    data = prefix + text.encode()
    if where == "meta":
        data = data.replace(b"# b: 2", b"# b: caf\xe9")
    else:  # latin-1 'µ' in the third data row
        lines = data.split(b"\n")
        lines[5] += b" \xb5"
        data = b"\n".join(lines)
    byte = "0xE9" if where == "meta" else "0xB5"
    raises(data, rf"^line {line}: not UTF-8 text \(byte {byte} at offset \d+ cannot be decoded\); "
                 r"save the file as UTF-8 CSV$", line, None)


def test_utf16_hint():
    data = make_csv(columns_for("steady", 12)).encode("utf-16")
    raises(data, r"not UTF-8 text.*looks like UTF-16", 1, None)


# ----------------------------------------------------------------------------- header errors


@pytest.mark.parametrize("text", ["", "   \n\n", b"", b"\xef\xbb\xbf\r\n", ",,\n , \n"])
def test_empty_file(text):
    raises(text, r"the file is empty", None, None)


def test_no_header():
    raises("# source: x\n# just a comment\n\n", r"no header line: the file has only comment", None, None)


@pytest.mark.parametrize(
    "header, match",
    [
        ("a,b,c", r"unknown columns a, b, c: expected t,x,F \(timeseries\), v,F \(steady\) or "
                  r"k,F_ba \(breakaway\)$"),
        ("t,x,force", r"unknown columns t, x, force: expected t,x,F"),
        ("t,x,f", r"unknown columns t, x, f: .*did you mean 'F' for 'f'\?"),
        ("T,X,F", r"did you mean 't' for 'T', 'x' for 'X'\?"),
        ("K,f_BA", r"did you mean 'k' for 'K', 'F_ba' for 'f_BA'\?"),
        ("t;x;F", r"unknown columns t;x;F: .*';' as separator"),
        ("0.0,1.5,2.5", r"the first line looks like data"),
    ],
)
def test_unknown_columns(header, match):
    rows = "\n".join("1,2,3" for _ in range(12))
    raises(f"# s: 1\n{header}\n{rows}\n", match, 2, None)


def test_case_hint_for_given_kind():
    cols = columns_for("steady", 12)
    text = make_csv({"v": cols["v"], "f": cols["F"]})
    raises(text, r"missing column 'F' required for kind 'steady'; the header has v, f "
                 r"\(did you mean 'F' for 'f'\?\)", HEADER_LINE, "F", kind="steady")


def test_missing_required_column_with_explicit_kind_names_it():
    cols = columns_for("timeseries", 12)
    del cols["x"]
    raises(make_csv(cols), r"missing column 'x' required for kind 'timeseries'", HEADER_LINE, "x",
           kind="timeseries")


@pytest.mark.parametrize("dup", ["F", "t", "v"])
def test_duplicate_column(dup):
    cols = columns_for("timeseries", 12)
    text = make_csv(cols)
    lines = text.splitlines()
    lines = [lines[0] + f",{dup}"] + [line + ",1.0" for line in lines[1:]]
    pos = lines[0].split(",").index(dup) + 1
    raises("\n".join(lines), rf"duplicate column '{dup}' \(header positions {pos}, 5\)", HEADER_LINE, dup)


# ----------------------------------------------------------------------------- row errors


@pytest.mark.parametrize("cell_line, match", [("1.0,2.0", r"2 cells, expected 3 as in the header on line 1"),
                                              ("1.0,2.0,3.0,4.0", r"4 cells, expected 3"),
                                              ("5", r"1 cell, expected 3")])
def test_wrong_number_of_cells(cell_line, match):
    lines = make_csv(columns_for("timeseries", 12, optional=False)).splitlines()
    lines[7] = cell_line
    raises("\n".join(lines), match, 8, None)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize(
    "text, match",
    [
        ("abc", r"'abc' is not a number"),
        ("1;5", r"'1;5' is not a number"),
        ("0x10", r"'0x10' is not a number"),
        ("", r"empty cell: a number is required"),
        ("  ", r"empty cell"),
    ],
)
def test_non_numeric_cell(kind, text, match):
    cols = columns_for(kind, 12)
    column = REQUIRED[kind][-1]
    bad = with_cell(cols, column, 6, text)
    err = raises(make_csv(bad), match, 8, column)
    assert str(err).startswith(f"line 8, column '{column}': ")


def test_non_numeric_in_optional_column_is_validated():
    bad = with_cell(columns_for("breakaway", 12), "dwell", 3, "long")
    raises(make_csv(bad), r"line 5, column 'dwell': 'long' is not a number", 5, "dwell")


def test_first_bad_cell_in_file_order_is_reported():
    cols = with_cell(columns_for("timeseries", 12), "F", 9, "x1")
    cols["x"][4] = "y1"
    cols["v"][2] = "z1"  # the last column, but the earliest line: reported first
    raises(make_csv(cols), r"'z1' is not a number", 4, "v")


@pytest.mark.parametrize(
    "text, match",
    [
        ("nan", r"'nan' is not a finite number \(NaN is not allowed\)"),
        ("NaN", r"NaN is not allowed"),
        ("inf", r"'inf' is not a finite number \(Inf is not allowed\)"),
        ("-Infinity", r"Inf is not allowed"),
        ("1e999", r"'1e999' is not a finite number \(Inf is not allowed\)"),
    ],
)
@pytest.mark.parametrize("kind", KINDS)
def test_nan_inf(kind, text, match):
    column = REQUIRED[kind][0]
    bad = with_cell(columns_for(kind, 12), column, 10, text)
    raises(make_csv(bad), match, 12, column)


def test_non_increasing_t():
    cols = columns_for("timeseries", 12)
    cols["t"][7] = cols["t"][6]
    err = raises(make_csv(cols), r"t must be strictly increasing, but t = 0\.006 does not exceed "
                                 r"t = 0\.006 on line 8", 9, "t")
    assert err.message.startswith("t must be")


def test_decreasing_t():
    cols = columns_for("timeseries", 12)
    cols["t"][3] = 5.0
    raises(make_csv(cols), r"t = 0\.004 does not exceed t = 5\.0 on line 5", 6, "t")


def test_t_not_checked_when_ignored():
    cols = columns_for("timeseries", 12)
    cols["t"][:] = 0.0
    assert parse_csv(make_csv(cols), kind="steady").kind == "steady"


@pytest.mark.parametrize(
    "column, text, match",
    [
        ("k", "0", r"k, the actuation force rate, must be > 0 \(between 1e-30 and 1e\+30\), got 0"),
        ("k", "-2.5", r"must be > 0 \(.*\), got -2\.5"),
        ("k", "5e-324", r"must be > 0 \(between 1e-30 and 1e\+30\), got 5e-324"),
        ("F_ba", "1e31", r"F_ba must lie within 1e\+30 in magnitude, got 1e31"),
        ("dwell", "-1e300", r"dwell, a time, must be >= 0, got -1e300"),
        ("F_ba", "-0.1", r"F_ba is a magnitude and must be >= 0, got -0\.1"),
        ("dwell", "-1", r"dwell, a time, must be >= 0, got -1"),
        ("direction", "0", r"direction must be \+1 or -1, got 0"),
        ("direction", "2", r"direction must be \+1 or -1, got 2"),
        ("direction", "-0.5", r"direction must be \+1 or -1, got -0\.5"),
    ],
)
def test_value_constraints(column, text, match):
    bad = with_cell(columns_for("breakaway", 12), column, 5, text)
    raises(make_csv(bad), match, 7, column)


@pytest.mark.parametrize("column, text", [("F_ba", "0"), ("F_ba", "-0.0"), ("dwell", "0"),
                                          ("direction", "+1"), ("direction", "-1.0")])
def test_value_constraint_boundaries_accepted(column, text):
    ds = parse_csv(make_csv(with_cell(columns_for("breakaway", 12), column, 5, text)))
    assert ds.columns[column][5] == float(text)


@pytest.mark.parametrize("n", [0, 1, MIN_ROWS - 1])
def test_too_few_rows(n):
    cols = columns_for("steady", max(n, 1))
    text = make_csv(cols) if n else "v,F\n"
    match = (r"no data rows after the header on line 1; at least 10 are required" if n == 0
             else rf"only {n} data rows? \(lines 2 to {n + 1}\); at least 10 are required")
    raises(text, match, None, None)


def test_exactly_min_rows_is_enough():
    assert parse_csv(make_csv(columns_for("steady", MIN_ROWS))).n == MIN_ROWS


# ----------------------------------------------------------------------------- size, files


@pytest.mark.parametrize(
    "size, limit, match",
    [
        (int(25.3 * 1024 * 1024), DEFAULT_MAX_BYTES, r"^file is 25\.3 MB; the limit is 20\.0 MB$"),
        (2000, 1024, r"^file is 2\.0 kB; the limit is 1\.0 kB$"),
        (150, 100, r"^file is 150 bytes; the limit is 100 bytes$"),
        (DEFAULT_MAX_BYTES + 1, DEFAULT_MAX_BYTES, r"^file is 20971521 bytes; the limit is 20971520 bytes$"),
    ],
)
def test_size_limit(size, limit, match):
    # not a CSV at all: the size is checked before anything is parsed
    raises(b"\xff" * size, match, None, None, max_bytes=limit)


def test_size_limit_str_counts_utf8_bytes():
    text = make_csv(columns_for("steady", 12), meta={"note": "µ" * 200})
    nbytes = len(text.encode())
    assert parse_csv(text, max_bytes=nbytes).n == 12
    raises(text, r"the limit is", None, None, max_bytes=nbytes - 1)


def test_read_csv(tmp_path):
    cols = columns_for("breakaway", 30)
    path = tmp_path / "ba.csv"
    path.write_bytes(b"\xef\xbb\xbf" + make_csv(cols, meta={"s": "1000"}, newline="\r\n").encode())
    ds = read_csv(path)
    assert ds.kind == "breakaway" and ds.n == 30 and ds.meta_float("s") == 1000.0
    np.testing.assert_allclose(ds.columns["F_ba"], cols["F_ba"], rtol=0, atol=1e-12)
    assert read_csv(str(path), kind="breakaway").n == 30


def test_read_csv_checks_size_before_reading(tmp_path, monkeypatch):
    path = tmp_path / "big.csv"
    with open(path, "wb") as fh:  # sparse: 25.3 MB on stat, nothing written
        fh.truncate(int(25.3 * 1024 * 1024))

    def no_open(*a, **k):
        raise AssertionError("the file must not be opened")

    monkeypatch.setattr("breakaway.identify.csvdata.open", no_open, raising=False)
    with pytest.raises(DataError, match=r"^file is 25\.3 MB; the limit is 20\.0 MB$") as info:
        read_csv(path)
    assert (info.value.line, info.value.column) == (None, None)


def test_read_csv_missing_file(tmp_path):
    with pytest.raises(DataError, match=r"cannot read '.*nope\.csv': No such file"):
        read_csv(tmp_path / "nope.csv")


# ------------------------------------------------------------------- large files
# (speed is measured in benchmarks/bench_identify.py, never asserted in a test)


def test_20000_rows_round_trip():
    n = 20_000
    cols = columns_for("timeseries", n)
    ds = parse_csv(make_csv(cols, meta={"source": "generated"}).encode())
    assert ds.n == n
    np.testing.assert_allclose(ds.columns["x"], cols["x"], rtol=0, atol=1e-12)


def test_error_in_large_file_is_located():
    cols = with_cell(columns_for("timeseries", 20_000), "x", 15_000, "1.2.3")
    with pytest.raises(DataError, match=r"line 15002, column 'x': '1\.2\.3' is not a number"):
        parse_csv(make_csv(cols).encode())


def test_units_in_the_header_are_stripped_and_rotary_ones_recorded():
    rows = "".join(f"{i * 0.001},{i * 1e-4},{1 + i}\n" for i in range(12))
    data = parse_csv("t [s],x [rad],F (N·m)\n" + rows)
    assert list(data.columns) == ["t", "x", "F"]
    assert data.meta["units"] == "rotary"
    linear = parse_csv("t (s),x [m],F [N]\n" + rows)
    assert "units" not in linear.meta


def test_positions_in_degrees_put_every_angle_in_degrees():
    rows = "".join(f"{i * 0.001},{i * 1e-2},{1 + i}\n" for i in range(12))
    data = parse_csv("t [s],x [deg],F [N·m]\n" + rows)
    assert data.meta["units"] == "rotary" and data.angle == "deg"
    assert [data.unit(u) for u in ("N", "m", "m/s", "1/m", "kg", "N·s/m")] == [
        "N·m", "deg", "deg/s", "1/deg", "N·m·s²/deg", "N·m·s/deg"]
    in_radians = parse_csv("t [s],x [rad],F [N·m]\n" + rows)
    assert in_radians.angle == "rad" and in_radians.unit("kg") == "kg·m²"
