"""Export: each plot's data as CSV (what is plotted, point for point) and as PNG."""

from __future__ import annotations

import csv
import io

import pytest

from breakaway.frame import stribeck_curve
from breakaway.params import DEFAULTS

pytestmark = pytest.mark.browser

HEADERS = {
    "stribeck": ["series", "v [m/s]", "Fss [N]"],
    "hysteresis": ["series", "x [m]", "F [N]"],
    "phase": ["series", "z [-]", "ẋ [m/s]"],
    "breakaway": ["series", "k [N/s]", "F_ba [N]"],
}
NAMES = {"stribeck": "Stribeck curve", "hysteresis": "hysteresis loop",
         "phase": "phase family", "breakaway": "break-away curve"}


def download(explorer, button_name: str):
    with explorer.page.expect_download() as info:
        explorer.page.get_by_role("button", name=button_name, exact=True).click()
    return info.value


@pytest.mark.parametrize("plot", list(HEADERS))
def test_csv_export_holds_the_plotted_points(explorer, plot):
    explorer.open("?sim=0")
    file = download(explorer, f"Export {NAMES[plot]} as CSV")
    assert file.suggested_filename == f"breakaway-{plot}.csv"
    rows = list(csv.reader(io.StringIO(open(file.path(), encoding="utf-8").read())))
    assert rows[0] == HEADERS[plot]
    expected = [[trace["name"], x, y] for trace in explorer.traces(plot).values()
                for x, y in zip(trace["x"], trace["y"]) if x is not None and y is not None]
    assert len(rows) - 1 == len(expected)
    for row, (name, x, y) in zip(rows[1:], expected):
        assert row[0] == name and float(row[1]) == x and float(row[2]) == y


def test_stribeck_csv_is_the_model_curve(explorer):
    explorer.open("?sim=0&Fs=2&V=3")
    rows = list(csv.reader(open(download(explorer, "Export Stribeck curve as CSV").path(),
                                encoding="utf-8")))
    p = {**DEFAULTS, "Fs": 2.0, "V": 3.0}
    v, F = stribeck_curve(p["Fc"], p["Fs"], p["V"], p["delta"], p["sigma"])
    assert len(rows) == 1 + len(v)
    for row, v_i, F_i in zip(rows[1:], v, F):
        assert float(row[1]) == pytest.approx(v_i, rel=1e-6)
        assert float(row[2]) == pytest.approx(F_i, rel=1e-6)


def test_png_export(explorer):
    explorer.open("?sim=0")
    file = download(explorer, "Export break-away curve as PNG")
    assert file.suggested_filename == "breakaway-breakaway.png"
    with open(file.path(), "rb") as handle:
        data = handle.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 5000
