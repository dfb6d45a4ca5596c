"""Export: every plot's data as CSV (what is plotted, point for point, under its title and
parameters), and its figure as PNG and SVG with the title and a caption line of the
parameters it was drawn with, units included, so that a slide explains itself."""

from __future__ import annotations

import base64
import csv
import io
import struct

import pytest

from breakaway.frame import stribeck_curve
from breakaway.params import DEFAULTS

pytestmark = pytest.mark.browser

HEADERS = {
    "stribeck": ["series", "v [m/s]", "Fss [N]"],
    "hysteresis": ["series", "x [m]", "F [N]"],
    "phase": ["series", "z [-]", "ẋ [m/s]"],
    "breakaway": ["series", "k [N/s]", "F_ba [N]"],
    "ramp": ["series", "t [s]", "u, F [N]", "ẋ [m/s]"],
    "loop-position": ["series", "t [s]", "r, x [m]"],
    "loop-error": ["series", "t [s]", "e = r − x [m]"],
    "loop-force": ["series", "t [s]", "u, F [N]"],
}
NAMES = {"stribeck": "Stribeck curve", "hysteresis": "hysteresis loop",
         "phase": "phase family", "breakaway": "break-away curve",
         "ramp": "the ramp experiment", "loop-position": "control loop position",
         "loop-error": "control loop error", "loop-force": "control loop force"}
TITLES = {"stribeck": "Stribeck curve", "hysteresis": "Presliding hysteresis",
          "phase": "Presliding phase family", "breakaway": "Break-away force",
          "ramp": "The ramp experiment", "loop-position": "Control loop: position",
          "loop-error": "Control loop: error", "loop-force": "Control loop: force"}
#: What each plot's caption names (its parameters with their units).
CAPTIONS = {
    "stribeck": "Fc = 1 N, Fs = 1.5 N, V = 100 m/s, δ = 1, σ = 0 N·s/m",
    "hysteresis": "σ = 0 N·s/m, s = 1 1/m",
    "phase": "k = 1 N/s, z* = 0.95, F̂ = avg",
    "breakaway": "k = 1 N/s, z* = 0.95, F̂ = avg",
    "ramp": "k = 1 N/s, m = 0.0001 kg, F̂ = avg",
    "loop-position": "a step reference, Kp = 0.03 N/m, Ki = 3 N/(m·s), Kd = 0.003 N·s/m",
    "loop-error": "m_loop = 0.00001 kg, h = 10 m",
    "loop-force": "Fc = 1 N, Fs = 1.5 N",
}
#: The exported image [px]: 1200×720 at twice the pixels.
PNG_SIZE = (2400, 1440)


def download(explorer, button_name: str):
    with explorer.page.expect_download() as info:
        explorer.page.get_by_role("button", name=button_name, exact=True).click()
    return info.value


def open_with_every_plot(explorer) -> None:
    explorer.open("?sim=0")
    explorer.page.evaluate("window.breakaway.loopReady()")


def rows_of(file) -> list[list[str]]:
    return list(csv.reader(io.StringIO(open(file.path(), encoding="utf-8").read())))


def test_every_plots_csv_export_holds_the_plotted_points(explorer):
    open_with_every_plot(explorer)
    for plot in HEADERS:
        file = download(explorer, f"Export {NAMES[plot]} as CSV")
        assert file.suggested_filename == f"breakaway-{plot}.csv"
        rows = rows_of(file)
        assert rows[0] == [f"# title: {TITLES[plot]}"]
        assert rows[1][0].startswith("# parameters: ") and CAPTIONS[plot] in ",".join(rows[1]), plot
        assert rows[2] == HEADERS[plot]
        traces = explorer.page.evaluate("""(id) => document.getElementById('plot-' + id).data.map(t => (
            {name: t.name, x: Array.from(t.x), y: Array.from(t.y), right: t.yaxis === 'y2'}))""", plot)
        expected = [[trace["name"], x, y, trace["right"]] for trace in traces
                    for x, y in zip(trace["x"], trace["y"]) if x is not None and y is not None]
        assert len(rows) - 3 == len(expected), plot
        for row, (name, x, y, right) in zip(rows[3:], expected):
            assert row[0] == name and float(row[1]) == x
            # a trace on the right axis (the ramp's ẋ) writes its values in that column
            assert float(row[3] if right else row[2]) == y
            assert len(row) == len(HEADERS[plot]) and (not right or row[2] == "")


def test_stribeck_csv_is_the_model_curve(explorer):
    explorer.open("?sim=0&Fs=2&V=3")
    rows = rows_of(download(explorer, "Export Stribeck curve as CSV"))[3:]
    p = {**DEFAULTS, "Fs": 2.0, "V": 3.0}
    v, F = stribeck_curve(p["Fc"], p["Fs"], p["V"], p["delta"], p["sigma"])
    assert len(rows) == len(v)
    for row, v_i, F_i in zip(rows, v, F):
        assert float(row[1]) == pytest.approx(v_i, rel=1e-6)
        assert float(row[2]) == pytest.approx(F_i, rel=1e-6)


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


#: Dark pixels in each band of rows of a PNG, decoded by the browser: [title and caption
#: band, the rest].
INK = """async ([png, band]) => {
  const image = new Image();
  image.src = `data:image/png;base64,${png}`;
  await image.decode();
  const canvas = document.createElement('canvas');
  canvas.width = image.width;
  canvas.height = image.height;
  const ctx = canvas.getContext('2d');
  ctx.drawImage(image, 0, 0);
  const count = (top, bottom) => {
    const pixels = ctx.getImageData(0, top, image.width, bottom - top).data;
    let dark = 0;
    for (let i = 0; i < pixels.length; i += 4) if (pixels[i] + pixels[i + 1] + pixels[i + 2] < 300) dark += 1;
    return dark;
  };
  return [count(0, band), count(band, image.height)];
}"""


def test_every_plots_png_export_is_titled_and_captioned(explorer):
    open_with_every_plot(explorer)
    for plot in HEADERS:
        file = download(explorer, f"Export {NAMES[plot]} as PNG")
        assert file.suggested_filename == f"breakaway-{plot}.png"
        data = open(file.path(), "rb").read()
        assert png_size(data) == PNG_SIZE, plot
        # the title and the caption lines above the plot: ink in the top band, where the
        # page's own figures leave an 8-px margin
        title, rest = explorer.page.evaluate(INK, [base64.b64encode(data).decode(), 120])
        assert title > 1000 and rest > title, plot


def test_svg_export_holds_the_title_and_the_caption(explorer):
    open_with_every_plot(explorer)
    for plot in ("ramp", "loop-force"):
        file = download(explorer, f"Export {NAMES[plot]} as SVG")
        assert file.suggested_filename == f"breakaway-{plot}.svg"
        text = open(file.path(), encoding="utf-8").read()
        assert text.startswith("<svg") and 'width="1200"' in text
        assert TITLES[plot] in text and CAPTIONS[plot] in text.replace("&amp;", "&")


def test_a_presentation_export_is_in_large_type(explorer):
    explorer.open("?sim=0&present=1")
    small = explorer.page.evaluate("""async () => {
      const { imageFigure } = await import('/js/plots/export.js');
      const figure = { data: [], layout: { xaxis: {}, yaxis: {}, margin: { t: 8 } } };
      const described = { title: 'T', caption: 'a, b', figure };
      return [imageFigure(described, { present: false }).layout.title.font.size,
              imageFigure(described, { present: true }).layout.title.font.size,
              imageFigure(described, { present: true, dark: true }).layout.paper_bgcolor];
    }""")
    assert small[0] < small[1] and small[2] == "#ffffff"
