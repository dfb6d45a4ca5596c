"""The data panel: upload, fit as a background job, show the diagnosis, use the fitted
parameters, cancel, samples, downloads, and bad files."""

from __future__ import annotations

import csv
import io
import json
import math
import urllib.request
from urllib.parse import parse_qs, urlparse

import numpy as np
import pytest

from breakaway.identify import identify, parse_csv
from breakaway.identify.samples import SAMPLES
from breakaway.identify.synthetic import make_dataset, to_csv

from browser_model import assert_plots_match_model, values

pytestmark = pytest.mark.browser

PANEL = "#data-panel"


def synthetic_csv(kind: str, effects: tuple[str, ...], seed: int, **kwargs) -> str:
    data, _ = make_dataset(kind, effects, seed=seed, **kwargs)
    return to_csv(data)


def engine_report(text: str) -> dict:
    return identify(parse_csv(text.encode()))


def upload(explorer, text: str, name: str = "data.csv") -> None:
    explorer.page.get_by_label("Data file", exact=True).set_input_files(
        {"name": name, "mimeType": "text/csv", "buffer": text.encode()})


def wait_for(explorer, *states: str) -> str:
    selector = ", ".join(f'{PANEL}[data-state="{state}"]' for state in states)
    explorer.page.wait_for_selector(selector, timeout=60_000)
    return explorer.page.locator(PANEL).get_attribute("data-state")


def shown_number(explorer, metric: str) -> float:
    return float(explorer.page.locator(f'#fit-error-table td[data-metric="{metric}"]').inner_text())


def assert_error_table_matches(explorer, report: dict) -> None:
    """The table's numbers (4 significant digits shown) are the engine's to 3."""
    expected = {"error_before": report["error_before"], "error_after": report["error_after"],
                "heldout_before": report["heldout"]["before"],
                "heldout_after": report["heldout"]["after"], "noise_floor": report["noise_floor"]}
    for metric, value in expected.items():
        assert shown_number(explorer, metric) == pytest.approx(value, rel=1e-3), metric
    assert shown_number(explorer, "error_after") < shown_number(explorer, "error_before")
    assert shown_number(explorer, "heldout_after") < shown_number(explorer, "heldout_before")


def shown_effects(explorer) -> list[str]:
    return explorer.page.locator("#fit-effects .effect-name").all_inner_texts()


def plot_traces(explorer, plot_id: str) -> dict[str, dict]:
    traces = explorer.page.evaluate(
        """(id) => document.getElementById(id).data.map(t => (
            {name: t.name, x: Array.from(t.x), y: Array.from(t.y)}))""", plot_id)
    return {trace["name"]: trace for trace in traces}


def job_status(server_url: str, job_id: str) -> dict:
    with urllib.request.urlopen(f"{server_url}/api/fit/jobs/{job_id}") as response:
        return json.load(response)


@pytest.mark.parametrize(("kind", "effect", "regressor"), [
    ("steady", "offset", "v"),
    ("breakaway", "dwell", "dwell"),
])
def test_upload_names_the_undeclared_effect_and_the_error_falls(explorer, kind, effect,
                                                                regressor):
    text = synthetic_csv(kind, (effect,), seed=1)
    report = engine_report(text)
    assert report["effects"] == [effect]
    explorer.open("?sim=0")
    upload(explorer, text)
    assert wait_for(explorer, "done", "error") == "done"
    page = explorer.page
    assert shown_effects(explorer) == [effect]
    assert page.locator(f'#fit-steps li[data-effect="{effect}"]').inner_text().startswith(effect)
    assert report["steps"][0]["evidence"][:40] in page.locator("#fit-steps").inner_text()
    assert_error_table_matches(explorer, report)
    assert "white" in page.locator("#fit-verdict").inner_text()
    # the parameter table: final values ± stderr, to the shown 4 significant digits
    row = page.locator('#fit-param-table tr[data-param="Fc"] td[data-model="final"]').inner_text()
    value, stderr = (float(part) for part in row.split("±"))
    assert value == pytest.approx(report["final"]["params"]["Fc"], rel=1e-3)
    assert stderr == pytest.approx(report["final"]["stderr"]["Fc"], rel=1e-1)

    # the plots: measured with both models, residuals, and one plot against the regressor
    data = parse_csv(text.encode())
    model = plot_traces(explorer, "fit-plot-model")
    assert set(model) == {"measured", "base model", "final model"}
    measured = data.columns["F" if kind == "steady" else "F_ba"]
    assert sorted(values(model["measured"]["y"])) == pytest.approx(sorted(measured), rel=1e-9)
    residual = plot_traces(explorer, "fit-plot-residual")
    after = values(residual["after (final model)"]["y"])
    assert math.sqrt(np.mean(after**2)) == pytest.approx(report["error_after"], rel=1e-6)
    before = values(residual["before (base model)"]["y"])
    assert math.sqrt(np.mean(before**2)) == pytest.approx(report["error_before"], rel=1e-6)
    evidence = plot_traces(explorer, f"fit-plot-effect-{effect}")
    assert sorted(evidence["before (base model)"]["x"]) == pytest.approx(
        sorted(data.columns[regressor]), rel=1e-12)
    assert explorer.page.evaluate("window.breakaway.fitReport().effects") == [effect]


def test_drop_a_file_on_the_drop_zone(explorer):
    text = synthetic_csv("breakaway", ("dwell",), seed=2)
    report = engine_report(text)
    explorer.open("?sim=0")
    zone = explorer.page.locator("#drop-zone")
    assert zone.is_visible()
    explorer.page.evaluate("""(text) => {
        const transfer = new DataTransfer();
        transfer.items.add(new File([text], 'dropped.csv', {type: 'text/csv'}));
        const zone = document.getElementById('drop-zone');
        for (const type of ['dragenter', 'dragover', 'drop']) {
            zone.dispatchEvent(new DragEvent(type, {dataTransfer: transfer, bubbles: true,
                                                    cancelable: true}));
        }
    }""", text)
    assert wait_for(explorer, "done", "error") == "done"
    assert shown_effects(explorer) == report["effects"] == ["dwell"]
    assert "dropped.csv" in explorer.page.locator("#fit-meta").inner_text()
    assert_error_table_matches(explorer, report)


def test_panel_layout_at_desktop_and_phone_width(explorer):
    text = synthetic_csv("steady", ("offset",), seed=1)
    page = explorer.page
    for width, height in ((1280, 800), (390, 844)):
        page.set_viewport_size({"width": width, "height": height})
        explorer.open("?sim=0")
        upload(explorer, text)
        assert wait_for(explorer, "done", "error") == "done"
        layout = page.evaluate("""() => {
            const box = (el) => el.getBoundingClientRect().toJSON();
            return {scrollWidth: document.documentElement.scrollWidth,
                    panel: box(document.getElementById('data-panel')),
                    plots: box(document.getElementById('plots')),
                    controls: box(document.getElementById('controls')),
                    fitPlots: [...document.querySelectorAll('.fit-plot')].filter((el) => el.offsetParent).map(box)};
        }""")
        assert layout["scrollWidth"] <= width
        assert layout["panel"]["top"] >= layout["plots"]["bottom"]  # below the plots
        assert len(layout["fitPlots"]) == 3
        for plot in layout["fitPlots"]:
            assert plot["left"] >= 0 and plot["right"] <= width and plot["height"] >= 200
        if width == 1280:  # beside the controls, in the plot column
            assert layout["panel"]["left"] >= layout["controls"]["right"]


def test_malformed_file_shows_line_and_column_and_the_explorer_keeps_working(explorer):
    rows = "".join(f"{0.01 * i},{1 + 0.1 * i}\n" for i in range(1, 14))
    text = f"v,F\n{rows}0.14,abc\n0.15,2\n"
    explorer.open("?sim=0")
    upload(explorer, text, "bad.csv")
    assert wait_for(explorer, "done", "error") == "error"
    alert = explorer.page.locator("#fit-error")
    assert alert.is_visible() and alert.get_attribute("role") == "alert"
    message = alert.inner_text()
    assert "line 15" in message and "column 'F'" in message and "'abc' is not a number" in message
    assert explorer.page.locator("#fit-results").is_hidden()
    assert explorer.page.locator("#server-error").is_hidden()
    # the browser logs the 422 itself; that one line is expected, nothing else
    logged = "console: Failed to load resource: the server responded with a status of 422"
    assert len(explorer.problems) == 1 and explorer.problems[0].startswith(logged)
    explorer.problems.clear()
    # the explorer still redraws
    frames = explorer.frames()
    slider = explorer.page.get_by_label("Fs [N] slider", exact=True)
    slider.focus()
    slider.press("PageUp")
    explorer.ready()
    assert explorer.frames() > frames
    assert explorer.state()["Fs"] > 1.5
    assert_plots_match_model(explorer)


def slider_position(value: float, low: float, high: float, steps: int = 1000,
                    first: int = 0) -> int:
    fraction = (math.log10(value) - math.log10(low)) / (math.log10(high) - math.log10(low))
    return min(steps, max(first, round(first + fraction * (steps - first))))


def test_use_these_parameters_moves_the_sliders(explorer):
    text = synthetic_csv("steady", ("viscous",), seed=3)
    report = engine_report(text)
    assert report["effects"] == ["viscous"]
    fitted = {name: float(f"{report['final']['params'][name]:.6g}")
              for name in ("Fc", "Fs", "V", "delta", "sigma")}
    explorer.open("?sim=0")
    page = explorer.page
    before = {name: page.get_by_label(f"{label} slider", exact=True).input_value()
              for name, label in (("Fc", "Fc [N]"), ("Fs", "Fs [N]"), ("V", "V [m/s]"),
                                  ("delta", "δ (delta)"))}
    upload(explorer, text)
    assert wait_for(explorer, "done", "error") == "done"
    frames = explorer.frames()
    page.get_by_role("button", name="Use these parameters", exact=True).click()
    explorer.ready()
    assert explorer.frames() > frames
    labels = {"Fc": "Fc [N]", "Fs": "Fs [N]", "V": "V [m/s]", "delta": "δ (delta)",
              "sigma": "σ (sigma) [N·s/m]"}
    query = parse_qs(urlparse(page.url).query)
    state = explorer.state()
    for name, label in labels.items():
        assert float(page.get_by_label(label, exact=True).input_value()) == fitted[name]
        assert float(query[name][0]) == fitted[name]
        assert state[name] == fitted[name]
    assert query["s"] == ["1"]  # steady data do not determine s
    sliders = {name: int(page.get_by_label(f"{labels[name]} slider", exact=True).input_value())
               for name in labels}
    assert sliders["Fc"] == slider_position(fitted["Fc"], 0.01, 100)
    assert sliders["Fs"] == slider_position(fitted["Fs"], 0.01, 100)
    assert sliders["V"] == slider_position(fitted["V"], 1e-4, 1e4)
    # the δ slider skips δ = 0: positions above it are one fewer
    assert sliders["delta"] == round((fitted["delta"] + 4) / 0.05) - (fitted["delta"] > 0)
    assert all(str(sliders[name]) != before[name] for name in before)
    # σ ≈ 54 N·s/m is beyond its slider (≤ 10): the range widens to the data's scale
    assert fitted["sigma"] > 10
    note = page.locator("#use-note").inner_text()
    assert "slider ranges widened to the data's scale: σ 0 … 1000" in note
    assert sliders["sigma"] == 1 + round((math.log10(fitted["sigma"]) + 4) / 7 * 999)
    assert_plots_match_model(explorer, state)
    # the measured points sit on the Stribeck plot
    measured = explorer.traces("stribeck")["measured"]
    data = parse_csv(text.encode())
    assert sorted(values(measured["y"])) == pytest.approx(sorted(data.columns["F"]), rel=1e-9)


def test_new_fit_replaces_a_running_one_and_cancel_ends_in_cancelled(explorer, server_url):
    long_text = synthetic_csv("timeseries", ("viscous", "asymmetry"), seed=3, n=20000)
    page = explorer.page
    explorer.open("?sim=0")
    upload(explorer, long_text, "long.csv")
    page.wait_for_selector(f"{PANEL}[data-job]")
    first = page.locator(PANEL).get_attribute("data-job")
    # the sliders keep working while the fit runs in a server thread
    during = page.evaluate("""async () => {
        const slider = document.getElementById('Fc-range');
        slider.value = String(Number(slider.value) - 20);
        slider.dispatchEvent(new Event('input', {bubbles: true}));
        await window.breakaway.ready();
        return document.getElementById('data-panel').dataset.state;
    }""")
    assert during == "running"
    assert_plots_match_model(explorer)
    # a new upload cancels the running fit
    small = synthetic_csv("steady", ("offset",), seed=1)
    upload(explorer, small, "small.csv")
    assert wait_for(explorer, "done", "error") == "done"
    assert shown_effects(explorer) == ["offset"]
    page.wait_for_function(
        "async (id) => (await (await fetch('/api/fit/jobs/' + id)).json()).status === 'cancelled'",
        arg=first, polling=200, timeout=60_000)
    # Cancel
    upload(explorer, long_text, "long.csv")
    page.wait_for_selector(f"{PANEL}[data-job]")
    second = page.locator(PANEL).get_attribute("data-job")
    assert second != first
    page.get_by_role("button", name="Cancel", exact=True).click()
    assert wait_for(explorer, "done", "error", "cancelled") == "cancelled"
    assert job_status(server_url, second)["status"] == "cancelled"
    assert page.locator("#fit-results").is_hidden()
    assert page.locator("#fit-error").is_hidden()
    assert "cancelled" in page.locator("#fit-message").inner_text()
    assert page.get_by_role("button", name="Cancel", exact=True).is_disabled()


def test_a_sample_loads_and_fits(explorer):
    sample = SAMPLES["mystery-b"]
    report = engine_report(sample.csv())
    assert report["effects"] == ["ripple"]
    explorer.open("?sim=0")
    page = explorer.page
    select = page.get_by_label("Sample", exact=True)
    select.select_option(label=sample.title)
    assert sample.description in page.locator("#sample-description").inner_text()
    page.get_by_role("button", name="Fit", exact=True).click()
    assert wait_for(explorer, "done", "error") == "done"
    # a mystery is a quiz: the diagnosis shows only after a guess
    assert not page.locator("#fit-effects").is_visible()
    model = plot_traces(explorer, "fit-plot-model")
    assert set(model) == {"measured", "base model"}
    residual = plot_traces(explorer, "fit-plot-residual")
    assert set(residual) == {"before (base model)"}
    reveal = page.get_by_role("button", name="Reveal the diagnosis")
    assert reveal.is_disabled()
    # the choices are the engine's library for the kind, viscous-power included
    guesses = page.get_by_label("Your guess", exact=True).locator("option")
    offered = [o for o in guesses.evaluate_all("els => els.map(e => e.value)") if o]
    assert offered == [*report["candidates"], "none", "outside"]
    assert "viscous-power" in offered
    page.get_by_label("Your guess", exact=True).select_option("backlash")
    reveal.click()
    assert page.locator("#quiz-result").inner_text() == "Not this time: the data hold ripple."
    assert shown_effects(explorer) == ["ripple"]
    assert_error_table_matches(explorer, report)
    assert "mystery-b.csv" in page.locator("#fit-meta").inner_text()
    ripple = plot_traces(explorer, "fit-plot-effect-ripple")
    assert len(ripple["before (base model)"]["x"]) == 4000  # 8000 rows, every 2nd
    # a time series determines s: "Use these parameters" sets it too
    page.get_by_role("button", name="Use these parameters", exact=True).click()
    explorer.ready()
    query = parse_qs(urlparse(page.url).query)
    for name in ("Fc", "Fs", "V", "delta", "s"):
        assert float(query[name][0]) == float(f"{report['final']['params'][name]:.6g}")
    assert query["sigma"] == ["0"]  # no viscous effect in this one
    assert_plots_match_model(explorer)


def test_downloads_report_and_residuals(explorer):
    text = synthetic_csv("steady", ("offset",), seed=1)
    report = engine_report(text)
    explorer.open("?sim=0")
    upload(explorer, text, "offset.csv")
    assert wait_for(explorer, "done", "error") == "done"
    page = explorer.page
    with page.expect_download() as info:
        page.get_by_role("button", name="Download report (JSON)", exact=True).click()
    download = info.value
    assert download.suggested_filename == "offset-report.json"
    saved = json.loads(open(download.path(), encoding="utf-8").read())
    assert saved.keys() == report.keys()
    for part in ("base", "final"):
        assert saved[part].keys() == report[part].keys()
        for name, value in report[part]["params"].items():
            assert saved[part]["params"][name] == pytest.approx(value, rel=1e-9)
    assert saved["effects"] == report["effects"]
    assert saved["error_after"] == pytest.approx(report["error_after"], rel=1e-9)

    with page.expect_download() as info:
        page.get_by_role("button", name="Download residuals (CSV)", exact=True).click()
    download = info.value
    assert download.suggested_filename == "offset-residuals.csv"
    lines = open(download.path(), encoding="utf-8").read().splitlines()
    assert lines[:2] == ["# kind: steady", "# effects: offset"]
    rows = list(csv.reader(io.StringIO("\n".join(lines[2:]))))
    assert rows[0] == ["v", "F_measured", "F_base", "F_final", "residual_before",
                       "residual_after"]
    assert len(rows) - 1 == report["n"]
    after = np.array([float(row[5]) for row in rows[1:]])
    assert math.sqrt(np.mean(after**2)) == pytest.approx(report["error_after"], rel=1e-6)


def test_panel_shows_warnings_undetermined_parameters_verdicts_and_structure(explorer):
    rng = np.random.default_rng(5)
    # steady friction with a hump around one speed: outside the library
    speeds = np.geomspace(1e-4, 0.3, 80)
    v = np.concatenate([-speeds[::-1], speeds])
    g = 10 + 5 * np.exp(-(np.abs(v) / 0.005) ** 1.5)
    hump = 2.0 * np.exp(-((np.log(np.abs(v)) - np.log(0.03)) / 0.4) ** 2)
    F = np.sign(v) * (g + hump) + 0.05 * rng.standard_normal(v.size)
    text = "v,F\n" + "".join(f"{a:.10g},{b:.10g}\n" for a, b in zip(v, F))
    report = engine_report(text)
    explorer.open("?sim=0")
    upload(explorer, text, "drag.csv")
    assert wait_for(explorer, "done", "error") == "done"
    page = explorer.page
    top = report["residual_structure"][0]
    row = page.locator(f'#fit-structure tr[data-against="{top["against"]}"]')
    assert row.locator("td").inner_text() == f"{round(100 * top['strength'])} %"
    page.locator("#fit-candidates-box summary").click()
    assert "viscous-power" in report["candidates"]
    for effect, verdict in report["candidates"].items():
        shown = page.locator(f'#fit-candidates tr[data-effect="{effect}"] td.verdict').inner_text()
        assert shown == ("accepted" if verdict["accepted"] else f"not accepted: {verdict['reason']}")

    # one rate only: a warning, and the parameters the data cannot fix are marked
    k = np.full(20, 5.0)
    text = "k,F_ba\n" + "".join(f"{a},{1.2 + 0.01 * b:.6f}\n" for a, b in zip(k, rng.standard_normal(20)))
    upload(explorer, text, "one-rate.csv")
    assert wait_for(explorer, "done", "error") == "done"
    assert page.locator('#fit-warnings li[data-code="single-rate"]').count() == 1
    cell = page.locator('#fit-param-table tr[data-param="V"] td[data-model="final"]')
    assert cell.get_attribute("data-determined") == "false"
    assert "not determined" in cell.inner_text()
    assert page.locator('#fit-param-table tr[data-param="Fs"] td[data-model="final"]'
                        ).get_attribute("data-determined") == "true"


def test_quiz_right_guess_and_the_plain_sample(explorer):
    sample = SAMPLES["mystery-e"]  # nothing missing
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_label("Sample", exact=True).select_option(label=sample.title)
    page.get_by_role("button", name="Fit", exact=True).click()
    assert wait_for(explorer, "done", "error") == "done"
    assert page.locator("#quiz").is_visible()
    page.get_by_label("Your guess", exact=True).select_option("none")
    page.get_by_role("button", name="Reveal the diagnosis").click()
    result = page.locator("#quiz-result")
    assert result.get_attribute("data-right") == "true"
    assert result.inner_text().startswith("Right: nothing is missing")
    # a file upload is no quiz
    upload(explorer, synthetic_csv("steady", ("offset",), seed=1))
    assert wait_for(explorer, "done", "error") == "done"
    assert not page.locator("#quiz").is_visible()
    assert shown_effects(explorer) == ["offset"]


def test_rotary_data_are_labelled_in_newton_metres(explorer):
    rng = np.random.default_rng(2)
    k = np.repeat(np.linspace(50.0, 250.0, 9), 4)
    F = 2.4 + 0.009 * k + 0.03 * rng.standard_normal(k.size)
    text = "k [N·m/s],F_ba [N·m]\n" + "".join(f"{a:.6g},{b:.6g}\n" for a, b in zip(k, F))
    explorer.open("?sim=0")
    upload(explorer, text, "joint.csv")
    assert wait_for(explorer, "done", "error") == "done"
    page = explorer.page
    title = page.evaluate("document.getElementById('fit-plot-model').layout.yaxis.title.text")
    assert title == "F_ba [N·m]"
    xtitle = page.evaluate("document.getElementById('fit-plot-model').layout.xaxis.title.text")
    assert xtitle == "k [N·m/s]"
    assert "fit RMSE [N·m]" in page.locator("#fit-error-table").inner_text()


def test_a_fitted_curve_sigma_v_to_the_n_is_named_and_not_put_on_the_linear_slider(explorer):
    text = synthetic_csv("steady", ("viscous-power",), seed=11)
    report = engine_report(text)
    assert report["effects"] == ["viscous-power"]
    explorer.open("?sim=0")
    page = explorer.page
    upload(explorer, text)
    assert wait_for(explorer, "done", "error") == "done"
    assert shown_effects(explorer) == ["viscous-power"]
    page.get_by_role("button", name="Use these parameters", exact=True).click()
    explorer.ready()
    note = page.locator("#use-note").inner_text()
    n = report["final"]["params"]["n"]
    assert "σ·|v|^n" in note and f"n = {float(f'{n:.6g}'):g}" in note
    assert float(page.get_by_label("σ (sigma) [N·s/m]", exact=True).input_value()) == 0


def test_a_time_series_fit_shows_the_hysteresis_and_a_window_of_time(explorer):
    # F against x, measured and fitted; over time a window of a few cycles, zoomable,
    # with the whole record in a range slider, not the record as one solid band
    text = synthetic_csv("timeseries", (), seed=4)
    data = parse_csv(text.encode())
    explorer.open("?sim=0")
    page = explorer.page
    upload(explorer, text)
    assert wait_for(explorer, "done", "error") == "done"
    model = plot_traces(explorer, "fit-plot-model")
    assert set(model) == {"measured", "base model", "final model"}
    assert page.evaluate("document.getElementById('fit-plot-model').layout.xaxis.title.text") == "x [m]"
    # every stride-th row of the record, as the panel's series holds it (4000 at most)
    stride = -(-data.n // 4000)
    assert values(model["measured"]["x"]) == pytest.approx(data.columns["x"][::stride], rel=1e-9)
    assert page.locator("#fit-time-card").is_visible()
    layout = page.evaluate("""() => { const l = document.getElementById('fit-plot-time').layout;
        return {range: l.xaxis.range, slider: l.xaxis.rangeslider.visible, title: l.xaxis.title.text}; }""")
    t = data.columns["t"]
    assert layout["slider"] is True and layout["title"] == "t [s]"
    assert layout["range"][0] == t[0] and t[0] < layout["range"][1] < 0.5 * t[-1]
    # the window holds the record's first six reversals of x (three cycles)
    x = data.columns["x"][t <= layout["range"][1]]
    turns = np.count_nonzero(np.diff(np.sign(np.diff(x[::max(1, x.size // 400)]))) != 0)
    assert 5 <= turns <= 12
    # steady data have no time
    upload(explorer, synthetic_csv("steady", (), seed=1))
    assert wait_for(explorer, "done", "error") == "done"
    assert page.locator("#fit-time-card").is_hidden()


def test_a_correlated_parameter_shows_the_combination_the_data_determine(explorer):
    explorer.open("?sim=0")
    tied = {"with": "V", "r": -0.99699, "slope": -613.33, "stderr": 0.01389}
    said = explorer.page.evaluate("""async (tied) => (await import('/js/datapanel/fitview.js'))
        .combination('Fc', {Fc: 8.96, V: 0.007036}, tied, 'N')""", tied)
    combined = 8.96 + 613.33 * 0.007036
    assert said == f"moves with V (r = −0.997): Fc + 613·V = {combined:.2f} ± 0.014 N is determined"
