"""POST /api/export: the data panel's downloads of a fitted model."""

from __future__ import annotations

import json

import pytest

from breakaway.export import export_model
from breakaway.identify.synthetic import make_dataset, to_csv


@pytest.fixture(scope="module")
def report(client):
    data, _ = make_dataset("timeseries", ("viscous",), seed=4, n=3000)
    response = client.post("/api/fit", files={"file": ("run.csv", to_csv(data), "text/csv")})
    assert response.status_code == 200, response.text
    return response.json()


@pytest.mark.parametrize("lang,filename,media", [
    ("python", "friction_model.py", "text/x-python"),
    ("c", "friction_model.c", "text/x-c"),
    ("json", "friction_model.json", "application/json"),
])
def test_the_downloads_are_the_command_line_s(client, report, lang, filename, media):
    response = client.post("/api/export", json={"report": report, "lang": lang})
    assert response.status_code == 200, response.text
    assert response.headers["content-type"].startswith(media)
    assert response.headers["content-disposition"] == f'attachment; filename="{filename}"'
    assert response.text == export_model(report, lang)


def test_the_report_of_a_fit_carries_what_the_export_needs(client, report):
    assert report["t_0"] == 0.0 and "s" in report["final"]["params"]
    document = json.loads(client.post("/api/export",
                                      json={"report": report, "lang": "json"}).text)
    assert document["params"]["sigma"] == report["final"]["params"]["sigma"]


def test_a_steady_report_takes_s_from_the_request(client):
    report = {"kind": "steady", "effects": [],
              "final": {"params": {"Fc": 1.0, "Fs": 1.5, "V": 0.1, "delta": 1.0}}}
    missing = client.post("/api/export", json={"report": report, "lang": "c"})
    assert missing.status_code == 422
    assert missing.json()["detail"][0]["loc"] == ["body", "report", "final", "params", "s"]
    given = client.post("/api/export", json={"report": report, "lang": "c", "s": 200.0})
    assert given.status_code == 200 and "BK_S = 200.0;" in given.text


@pytest.mark.parametrize("payload,loc", [
    ({"report": {"effects": []}, "lang": "c"}, ["body", "report", "final", "params"]),
    ({"report": {"final": {"params": {"Fc": 1.0}}, "effects": []}, "lang": "c"},
     ["body", "report", "final", "params", "Fs"]),
    ({"report": {"final": {"params": {"Fc": 1, "Fs": 2, "V": 1, "delta": 1, "s": 1,
                                      "alpha": 0.1}}, "effects": ["drift"]}, "lang": "json"},
     ["body", "report", "t_0"]),
    ({"report": [], "lang": "c"}, ["body", "report"]),
    ({"lang": "c"}, ["body", "report"]),
    ({"report": {}, "lang": "rust"}, ["body", "lang"]),
    ({"report": {}, "lang": "c", "s": -1}, ["body", "s"]),
    ({"report": {}, "lang": "c", "extra": 1}, ["body", "extra"]),
])
def test_bad_requests_are_422_naming_the_field(client, payload, loc):
    response = client.post("/api/export", json=payload)
    assert response.status_code == 422, response.text
    assert response.json()["detail"][0]["loc"] == loc
