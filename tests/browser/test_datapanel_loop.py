"""The data panel's way out for a fitted model: "Try this model in a control loop" (the
plant takes the fitted model and the loop its scale, or only the compensator takes it)
and the model's downloads as JSON, a Python module and a C99 file (POST /api/export),
with the server's sentence when an export fails."""

from __future__ import annotations

import json
from urllib.parse import parse_qs, urlparse

import pytest

from breakaway.export import export_model
from breakaway.identify.synthetic import make_dataset, to_csv
from breakaway.loop import loop_experiment
from breakaway.params import DEFAULTS, LOOP_COMMON, LOOP_DEFAULTS

pytestmark = pytest.mark.browser

LOOP = LOOP_DEFAULTS["presliding"]
PANEL = "#data-panel"


def fitted_upload(explorer, kind: str, **kwargs) -> dict:
    """Upload seeded synthetic data, wait for the fit; the page's report."""
    data, _ = make_dataset(kind, (), seed=1, **kwargs)
    explorer.page.get_by_label("Data file", exact=True).set_input_files(
        {"name": f"{kind}.csv", "mimeType": "text/csv", "buffer": to_csv(data).encode()})
    explorer.page.wait_for_selector(f'{PANEL}[data-state="done"], {PANEL}[data-state="error"]',
                                    timeout=60_000)
    assert explorer.page.locator(PANEL).get_attribute("data-state") == "done"
    return explorer.page.evaluate("window.breakaway.fitReport()")


def six(value: float) -> float:
    return float(f"{value:.6g}")


def four(value: float) -> float:
    return float(f"{value:.4g}")


def loop_ready(explorer) -> dict:
    return explorer.page.evaluate("window.breakaway.loopReady()")


def test_try_this_model_in_a_control_loop_carries_the_loop_to_its_scale(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    report = fitted_upload(explorer, "timeseries", n=4000)
    fitted = {name: six(report["final"]["params"][name]) for name in ("Fc", "Fs", "V", "delta", "s")}
    assert fitted["Fs"] == pytest.approx(15, rel=0.01) and fitted["s"] == pytest.approx(2000, rel=0.01)
    page.get_by_role("button", name="Try this model in a control loop", exact=True).click()
    explorer.ready()
    shown = loop_ready(explorer)
    state = explorer.state()
    # the plant: the fitted model, as "Use these parameters" sets it
    for name, value in fitted.items():
        assert state[name] == value
        assert shown["params"][name] == value
    assert state["sigma"] == 0
    # the loop: its defaults carried to the model's forces (× Fs/1.5) and lengths (× 1/s)
    force, length = fitted["Fs"] / DEFAULTS["Fs"], DEFAULTS["s"] / fitted["s"]
    expected = {"Kp": four(LOOP["Kp"] * force / length), "Ki": four(LOOP["Ki"] * force / length),
                "Kd": four(LOOP["Kd"] * force / length), "m_loop": four(LOOP["m"] * force / length),
                "h": four(LOOP["h"] * length)}
    for name, value in expected.items():
        assert state[name] == value, name
    assert shown["controller"]["Kp"] == expected["Kp"] and shown["params"]["m"] == expected["m_loop"]
    query = parse_qs(urlparse(page.url).query)
    assert float(query["Kp"][0]) == expected["Kp"] and float(query["s"][0]) == fitted["s"]
    # the page's run is the library's
    run = loop_experiment("presliding", {**{k: fitted[k] for k in ("Fc", "Fs", "V", "delta", "s")},
                                         "sigma": 0.0, "z_ba": DEFAULTS["z_ba"], "m": expected["m_loop"]},
                          {"Kp": expected["Kp"], "Ki": expected["Ki"], "Kd": expected["Kd"], "u_max": None},
                          {"kind": "step", "h": expected["h"], "w": LOOP["w"] * length, "f": LOOP["f"]},
                          LOOP_COMMON["duration"])
    assert shown["rms_error"] == pytest.approx(run["rms_error"], rel=1e-6)
    assert len(shown["stick_phases"]) == len(run["stick_phases"]) >= 5
    # the slider reaches the scale, the card is in view, the panel says what it set
    kp = int(page.get_by_label("Kp [N/m] slider", exact=True).input_value())
    assert 0 < kp < 1000
    top = page.evaluate("document.getElementById('card-loop').getBoundingClientRect().top")
    assert -1 <= top < 800
    note = page.locator("#use-note").inner_text()
    assert note.startswith("The plant takes the fitted model") and f"Kp = {expected['Kp']:g}" in note


def test_only_the_compensator_takes_the_fitted_model(explorer):
    explorer.open("?sim=0&ref=sine")
    page = explorer.page
    report = fitted_upload(explorer, "timeseries", n=4000)
    fitted = {name: six(report["final"]["params"][name]) for name in ("Fc", "Fs", "V", "delta")}
    page.get_by_label("Only the compensator takes the fitted model (the plant keeps the sliders)").check()
    page.get_by_role("button", name="Try this model in a control loop", exact=True).click()
    explorer.ready()
    shown = loop_ready(explorer)
    state = explorer.state()
    for name in ("Fc", "Fs", "V", "delta", "s"):
        assert state[name] == DEFAULTS[name]  # the plant keeps the sliders
    assert state["comp"] == "exact" and state["comp_model"] == "fitted"
    assert shown["compensation"] == {"scale": 1.0, "params": {**fitted, "sigma": 0.0}}
    assert page.get_by_label("Compensator's model", exact=True).input_value() == "fitted"
    # a compensator ten times too strong: the library's run of the same loop
    plant = {name: DEFAULTS[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "z_ba")}
    run = loop_experiment("presliding", {**plant, "m": LOOP["m"]},
                          {name: LOOP[name] for name in ("Kp", "Ki", "Kd", "u_max")},
                          {"kind": "sine", "h": LOOP["h"], "w": LOOP["w"], "f": LOOP["f"]},
                          LOOP_COMMON["duration"],
                          compensation={"scale": 1.0, "params": {**fitted, "sigma": 0.0}})
    assert shown["rms_error"] == pytest.approx(run["rms_error"], rel=1e-6)
    text = page.locator("#loop-explain").inner_text()
    assert (f"The compensator uses the fitted model (Fc = {fitted['Fc']:.4g} N, Fs = {fitted['Fs']:.4g} N, "
            f"V = {fitted['V']:.4g} m/s)" in text)
    assert "while the plant has the sliders' (Fc = 1 N, Fs = 1.5 N, V = 100 m/s)" in text
    assert parse_qs(urlparse(page.url).query)["cFs"] == [f"{fitted['Fs']:g}"]


@pytest.mark.parametrize("lang,button,filename,content_type,marker", [
    ("python", "Download model (Python)", "friction_model.py", "text/x-python; charset=utf-8", "def steady("),
    ("c", "Download model (C99)", "friction_model.c", "text/x-c; charset=utf-8", "double bk_step("),
    ("json", "Download model (JSON)", "friction_model.json", "application/json", None),
])
def test_the_fitted_model_downloads_as_code(explorer, lang, button, filename, content_type, marker):
    explorer.open("?sim=0&s=200")
    page = explorer.page
    report = fitted_upload(explorer, "steady")
    # steady data leave s open: the box holds the explorer's
    box = page.get_by_label("Presliding scale s for the model [1/m]", exact=True)
    assert box.input_value() == "200"
    with page.expect_response("**/api/export") as answer, page.expect_download() as info:
        page.get_by_role("button", name=button, exact=True).click()
    assert answer.value.headers["content-type"] == content_type
    download = info.value
    assert download.suggested_filename == filename
    text = open(download.path(), encoding="utf-8").read()
    assert text == export_model(report, lang, s=200.0)
    if marker:
        assert marker in text
    else:
        assert json.loads(text)["params"]["Fs"] == pytest.approx(report["final"]["params"]["Fs"], rel=1e-12)
    assert page.locator("#fit-error").is_hidden()


def test_a_failed_export_says_what_the_server_names(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    fitted_upload(explorer, "steady")
    box = page.get_by_label("Presliding scale s for the model [1/m]", exact=True)
    box.fill("-3")
    page.get_by_role("button", name="Download model (C99)", exact=True).click()
    error = page.locator("#fit-error")
    assert error.inner_text() == "The model could not be exported: the presliding scale s must be a number > 0."
    # the server's refusal: the request without s (a steady report has none)
    box.fill("1")

    def without_s(route):
        body = json.loads(route.request.post_data)
        body.pop("s")
        route.continue_(post_data=json.dumps(body))

    page.route("**/api/export", without_s)
    page.get_by_role("button", name="Download model (C99)", exact=True).click()
    page.wait_for_selector("#fit-error:not([hidden])")
    said = error.inner_text()
    assert said.startswith("The model could not be exported as C99: report (steady) has no presliding scale s")
    assert said.endswith("(HTTP 422, at report.final.params.s).")
    # the browser logs the 422 itself; that one line is expected, nothing else
    logged = "console: Failed to load resource: the server responded with a status of 422"
    assert len(explorer.problems) == 1 and explorer.problems[0].startswith(logged)
    explorer.problems.clear()
