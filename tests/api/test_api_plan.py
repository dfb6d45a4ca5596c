"""POST /api/plan: a report from /api/fit planned for; bad requests are 422 naming the
field; the route is in the OpenAPI document."""

from __future__ import annotations

import io
import json

import numpy as np
import pytest

from breakaway.identify.synthetic import to_csv
from breakaway.plan.checks import _ramps_record


@pytest.fixture(scope="module")
def report(client):
    """The report of ramps at high rates only (V and δ wholly open), through /api/fit."""
    csv = to_csv(_ramps_record(1, 40.0, 300.0, 0.005))
    answer = client.post("/api/fit", files={"file": ("ramps.csv", csv, "text/csv")})
    assert answer.status_code == 200
    return answer.json()


def test_a_fit_report_gets_a_plan_and_its_programme(client, report):
    answer = client.post("/api/plan", json={"report": report, "family": "ramps",
                                            "limits": {"u_max": 3.0}, "runs": 10})
    assert answer.status_code == 200
    plan = answer.json()
    assert plan["family"] == "ramps" and plan["targets"] == ["Fs", "V", "delta"]
    assert plan["design"]["runs"] == 10 and len(plan["design"]["rates"]) == 10
    assert plan["predicted"]["V"]["stderr_now"] is None
    assert plan["predicted"]["V"]["determined_after"] is True
    assert plan["limits"]["u_max"] == 3.0
    lines = [line for line in plan["programme"].splitlines() if not line.startswith("#")]
    assert lines[0] == "run,t,u"
    table = np.loadtxt(io.StringIO("\n".join(lines[1:])), delimiter=",")
    assert set(table[:, 0].astype(int)) == set(range(1, 11)) and table[:, 2].max() <= 3.0


def test_explorer_parameters_get_a_plan(client):
    answer = client.post("/api/plan", json={"params": {"Fc": 1.0, "Fs": 1.5, "V": 100.0},
                                            "family": "steady", "noise": 0.01})
    assert answer.status_code == 200
    plan = answer.json()
    assert plan["noise"] == 0.01 and plan["targets"] == ["Fc", "Fs", "V", "delta"]
    assert all(entry["stderr_now"] is None for entry in plan["predicted"].values())


@pytest.mark.parametrize("payload, loc", [
    ({"family": "ramps"}, ["body", "report"]),
    ({"family": "ramps", "params": {}, "report": {}}, ["body", "report"]),
    ({"family": "walk", "params": {}}, ["body", "family"]),
    ({"family": "ramps", "params": {}, "runs": 65}, ["body", "runs"]),
    ({"family": "ramps", "params": {}, "runs": 0}, ["body", "runs"]),
    ({"family": "ramps", "params": {}, "grid": 401}, ["body", "grid"]),
    ({"family": "ramps", "params": {}, "targets": ["W"]}, ["body", "targets", 0]),
    ({"family": "ramps", "params": {}, "ranges": {"V": [2.0, 1.0]}}, ["body", "ranges", "V"]),
    ({"family": "ramps", "params": {}, "limits": {"u_max": 0}}, ["body", "limits", "u_max"]),
    ({"family": "ramps", "params": {"Fc": 2.0, "Fs": 1.0}}, ["body", "params", "Fs"]),
    ({"family": "ramps", "params": {"delta": 0.0}}, ["body", "params", "delta"]),
    ({"family": "ramps", "report": {"kind": "steady"}}, ["body", "report", "final", "params"]),
    ({"family": "sine", "report": {"kind": "steady", "final": {"params": {
        "Fc": 1.0, "Fs": 1.5, "V": 0.01, "delta": 1.0}}}}, ["body", "ranges", "s"]),
])
def test_bad_requests_are_422_naming_the_field(client, payload, loc):
    answer = client.post("/api/plan", json=payload)
    assert answer.status_code == 422, answer.text
    assert answer.json()["detail"][0]["loc"] == loc


def test_a_report_with_a_field_of_the_wrong_type_is_422_not_500(client, report):
    for key, value in (("final", {"params": {"Fc": "1", "Fs": 1.5, "V": 1.0, "delta": 1.0}}),
                       ("extent", {"speeds": ["a", 1]}), ("units", [1, 2]),
                       ("noise_floor", "x")):
        broken = {**json.loads(json.dumps(report)), key: value}
        answer = client.post("/api/plan", json={"report": broken, "family": "ramps"})
        assert answer.status_code in (200, 422), (key, answer.text)


def test_the_route_is_documented(client):
    document = client.get("/openapi.json").json()
    operation = document["paths"]["/api/plan"]["post"]
    assert {"200", "422"} <= set(operation["responses"])
    request = document["components"]["schemas"]["PlanRequest"]["properties"]
    assert {"report", "params", "family", "limits", "runs", "noise", "targets"} <= set(request)
