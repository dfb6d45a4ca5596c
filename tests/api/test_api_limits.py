"""Degenerate numbers refused by name, one size limit with one status code, and error
messages of bounded size that never carry exception text."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from breakaway.api.app import create_app
from breakaway.api.schemas import MAGNITUDE

LEAKS = ("Traceback", "Error:", "ZeroDivision", "Overflow", "File \"")


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), raise_server_exceptions=False) as c:
        yield c


@pytest.mark.parametrize(("path", "body", "field"), [
    ("/api/explore", {"k": 5e-324}, ["k"]),
    ("/api/explore", {"V": 5e-324}, ["V"]),
    ("/api/explore", {"Fc": 1e300, "Fs": 1e301}, ["Fc"]),
    ("/api/explore", {"delta": 1e200}, ["delta"]),
    ("/api/simulate", {"k": [1.0, 5e-324]}, ["k", 1]),
    ("/api/simulate", {"k": [1.0], "m": 1e-300}, ["m"]),
    ("/api/simulate", {"k": [1.0], "model": "lugre", "sigma0": 1e308}, ["sigma0"]),
    ("/api/ramp", {"k": 5e-324}, ["k"]),
    ("/api/ramp", {"k": 1e300}, ["k"]),
    ("/api/ramp", {"k": 1.0, "s": 1e-320}, ["s"]),
])
def test_degenerate_numbers_are_refused_by_name(client, path, body, field):
    response = client.post(path, json=body)
    assert response.status_code == 422
    error = response.json()["detail"][0]
    assert error["loc"] == ["body", *field]
    assert f"between {MAGNITUDE[0]:g} and {MAGNITUDE[1]:g}" in error["msg"]
    assert not any(leak in response.text for leak in LEAKS)


def test_a_coefficient_that_may_be_zero_is_bounded_above_only(client):
    # a tiny σ is as good as 0 to every formula; one past 1e30 overflows them
    assert client.post("/api/explore", json={"sigma": 1e-310}).status_code == 200
    refused = client.post("/api/explore", json={"sigma": 1e31})
    assert refused.status_code == 422
    assert refused.json()["detail"][0]["loc"] == ["body", "sigma"]
    assert "at most 1e+30" in refused.json()["detail"][0]["msg"]


@pytest.mark.parametrize(("path", "body"), [
    ("/api/explore", {"k": MAGNITUDE[0], "s": MAGNITUDE[1], "V": MAGNITUDE[0]}),
    ("/api/explore", {"k": MAGNITUDE[1], "s": MAGNITUDE[0], "V": MAGNITUDE[1],
                      "Fc": MAGNITUDE[0], "Fs": MAGNITUDE[0], "delta": -MAGNITUDE[1]}),
    ("/api/simulate", {"k": [MAGNITUDE[0], MAGNITUDE[1]], "m": MAGNITUDE[1], "max_steps": 2000}),
    ("/api/ramp", {"k": MAGNITUDE[1], "s": MAGNITUDE[0], "max_steps": 2000}),
])
def test_the_ends_of_the_range_are_computed_or_refused_cleanly(client, path, body):
    response = client.post(path, json=body)
    assert response.status_code in (200, 422)
    assert not any(leak in response.text for leak in LEAKS)
    if response.status_code == 422:
        assert response.json()["detail"][0]["loc"][0] == "body"


@pytest.fixture
def small_limit(make_client):
    with make_client(max_upload_bytes=4096) as c:
        yield c


@pytest.mark.parametrize("size", [4097, 4096 + 40_000, 2_000_000])
@pytest.mark.parametrize("path", ["/api/fit", "/api/fit/jobs"])
def test_one_upload_limit_one_status(small_limit, path, size):
    # just over the limit (the file is read and measured), over it by more than the
    # multipart framing allowance (refused on the stream) and far over it: one answer
    body = b"v,F\n" + b"1,1\n" * ((size - 4) // 4) + b"1" * ((size - 4) % 4)
    assert len(body) == size
    response = small_limit.post(path, files={"file": ("big.csv", body, "text/csv")})
    assert response.status_code == 413
    error = response.json()["detail"][0]
    assert error == {"type": "body_too_large", "loc": ["body", "file"],
                     "msg": "file over the 4 KiB limit (4096 bytes)"}


def test_a_file_at_the_limit_is_read(small_limit):
    rows = "".join(f"{v},{1 + 0.1 / (1 + v)}\n" for v in range(1, 60))
    body = ("# kind: steady\nv,F\n" + rows).encode()
    body += b"#" * (4096 - len(body) - 1) + b"\n"
    assert len(body) == 4096
    response = small_limit.post("/api/fit", files={"file": ("ok.csv", body, "text/csv")})
    assert response.status_code != 413


def test_a_json_body_over_its_limit_names_the_body(client):
    response = client.post("/api/explore", content=b"{" + b" " * 70_000 + b"}",
                           headers={"Content-Type": "application/json"})
    assert response.status_code == 413
    assert response.json()["detail"][0]["loc"] == ["body"]
    assert "64 KiB limit" in response.json()["detail"][0]["msg"]


def test_csv_errors_echo_a_bounded_part_of_the_input(client):
    cell = "x" * 200_000
    body = f"# kind: steady\nv,F\n{cell},1\n".encode()
    response = client.post("/api/fit", files={"file": ("bad.csv", body, "text/csv")})
    assert response.status_code == 422
    assert len(response.content) <= 1024
    assert response.json()["detail"][0]["line"] == 3


@pytest.mark.parametrize("path", ["/api/fit", "/api/fit/jobs"])
@pytest.mark.parametrize(("meta", "message"), [
    ("# s: -1", "metadata 's' (the presliding scale) must be > 0, between 1e-30 and 1e+30, got '-1'"),
    ("# s: 1e-320", "metadata 's' (the presliding scale) must be > 0, between 1e-30 and 1e+30"),
    ("# F0: 1e400", "metadata 'f0' must be a finite number, got '1e400'"),
])
def test_bad_metadata_is_refused_before_a_job_starts(client, path, meta, message):
    rows = "\n".join(f"{k},{1.2 + 0.01 * k}" for k in range(1, 13))
    body = f"{meta}\nk,F_ba\n{rows}\n".encode()
    response = client.post(path, files={"file": ("bad.csv", body, "text/csv")})
    # a 422 naming the line at once: never a 202 for a job that would fail later
    assert response.status_code == 422
    error = response.json()["detail"][0]
    assert error["loc"] == ["body", "file"] and error["line"] == 1
    assert message in error["msg"]
    assert not any(leak in response.text for leak in LEAKS)


def test_a_method_an_api_path_does_not_take_is_405_with_allow(client):
    response = client.put("/api/explore", json={})
    assert response.status_code == 405
    assert response.headers["allow"] == "POST"
    assert response.json()["detail"][0]["type"] == "method_not_allowed"
    jobs = client.post("/api/fit/jobs/abc")
    assert jobs.status_code == 405 and jobs.headers["allow"] == "DELETE, GET, HEAD"


def test_an_unknown_api_path_is_404_not_the_page(client):
    response = client.get("/api/nothing/here")
    assert response.status_code == 404
    assert response.headers["content-type"] == "application/json"
    assert response.json()["detail"][0]["type"] == "not_found"
