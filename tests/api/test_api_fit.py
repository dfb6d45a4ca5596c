"""POST /api/fit and the fit jobs through the TestClient."""

from __future__ import annotations

import time

import numpy as np
import pytest

from breakaway.identify.synthetic import make_dataset, to_csv, with_force


def _csv(kind, effects=(), seed=0, **kwargs) -> bytes:
    data, _ = make_dataset(kind, effects, seed=seed, **kwargs)
    return to_csv(data).encode()


def _upload(content: bytes, name="data.csv"):
    return {"file": (name, content, "text/csv")}


def test_fit_reports_the_undeclared_effect(client):
    response = client.post("/api/fit", files=_upload(_csv("steady", ("offset",), seed=1)))
    assert response.status_code == 200
    report = response.json()
    assert report["kind"] == "steady"
    assert report["effects"] == ["offset"]
    assert report["error_after"] < 0.07 < report["error_before"]
    assert report["final"]["params"]["F_offset"] == pytest.approx(0.6, rel=0.1)
    assert report["heldout"]["after"] < report["heldout"]["before"]


def test_a_spike_in_the_upload_is_reported_by_its_line(client):
    # a steady file whose row at line 40 (a header and a kind line come first) glitched
    data, _ = make_dataset("steady", (), seed=2)
    force = data.columns["F"].copy()
    row = int(np.flatnonzero(data.lines == 40)[0])
    force[row] += 3.0
    response = client.post("/api/fit", files=_upload(to_csv(with_force(data, force)).encode()))
    assert response.status_code == 200
    report = response.json()
    outliers = [w for w in report["warnings"] if w["code"] == "outliers"]
    assert len(outliers) == 1 and outliers[0]["parameter"] == "F"
    assert outliers[0]["message"].startswith(f"1 of {data.n} rows (lines 40)")
    assert report["n"] == data.n - 1
    assert report["effects"] == [] and report["unexplained"] is False


def test_kind_form_field_overrides_detection(client):
    content = _csv("steady", (), seed=2)
    response = client.post("/api/fit", files=_upload(content), data={"kind": "timeseries"})
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"] == ["body", "file"]
    assert "missing column" in detail["msg"] and "'t'" in detail["msg"]


@pytest.mark.parametrize("content,line,column,message", [
    (b"t,x,F\n" + b"".join(f"{i},0,0\n".encode() for i in range(3)), None, None, "at least 10"),
    (b"t,x,F\n" + b"".join(f"{i},0,{'abc' if i == 4 else 1}\n".encode() for i in range(12)),
     6, "F", "'abc' is not a number"),
    (b"a,b\n1,2\n", 1, None, "unknown columns"),
    (b"", None, None, "empty"),
])
def test_bad_csv_names_line_and_column(client, content, line, column, message):
    response = client.post("/api/fit", files=_upload(content))
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert message in detail["msg"]
    assert detail["line"] == line
    assert detail["column"] == column
    assert "Traceback" not in response.text


def test_missing_file_is_a_422(client):
    response = client.post("/api/fit", data={"kind": "steady"})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"][-1] == "file"


def test_upload_over_the_limit_is_refused(make_client):
    with make_client(max_upload_bytes=2000) as small:
        response = small.post("/api/fit", files=_upload(_csv("steady", (), seed=0)))
    assert response.status_code in (413, 422)
    assert "limit" in response.text


def _wait(client, job_id, timeout=120.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        status = client.get(f"/api/fit/jobs/{job_id}").json()
        if status["status"] in ("done", "error", "cancelled"):
            return status
        time.sleep(0.05)
    raise AssertionError(f"job {job_id} did not end")


def test_job_runs_in_the_background_with_progress_and_series(client):
    response = client.post("/api/fit/jobs", files=_upload(_csv("breakaway", ("dwell",), seed=3)))
    assert response.status_code == 202
    job = response.json()
    assert job["status"] in ("queued", "running", "done")
    # the server answers other requests meanwhile
    assert client.get("/api/health").status_code == 200
    status = _wait(client, job["id"])
    assert status["status"] == "done" and status["progress"] == 1.0
    assert status["report"]["effects"] == ["dwell"]
    series = status["series"]
    assert series["axis"] == "k"
    assert series["effect_regressor"] == {"dwell": "dwell"}
    n = len(series["columns"]["k"])
    assert all(len(v) == n for v in series["columns"].values())
    residuals = client.get(f"/api/fit/jobs/{job['id']}/residuals.csv")
    assert residuals.status_code == 200
    lines = residuals.text.splitlines()
    assert lines[1] == "# effects: dwell"
    assert lines[2].split(",")[-2:] == ["residual_before", "residual_after"]
    assert len(lines) == 3 + 120


def test_job_can_be_cancelled(client):
    content = _csv("timeseries", ("backlash",), seed=4, n=20_000)
    job = client.post("/api/fit/jobs", files=_upload(content)).json()
    cancelled = client.delete(f"/api/fit/jobs/{job['id']}")
    assert cancelled.status_code == 200
    status = _wait(client, job["id"])
    assert status["status"] == "cancelled"
    assert status["report"] is None


def test_unknown_job_is_404(client):
    for response in (client.get("/api/fit/jobs/nope"), client.delete("/api/fit/jobs/nope"),
                     client.get("/api/fit/jobs/nope/residuals.csv")):
        assert response.status_code == 404
        assert response.json() == {"detail": [{"type": "not_found", "loc": [],
                                               "msg": "no such fit job"}]}
