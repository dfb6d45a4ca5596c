"""Delivery and failure paths: compressed static files with ETags, 429 with Retry-After
decided before the upload is read, and internal errors without exception text."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient

from breakaway.api.app import create_app
from breakaway.api.routers.assets import PLOTLY_BUNDLE
from breakaway.settings import get_settings

PLOTLY_JS = get_settings().frontend_dir / PLOTLY_BUNDLE


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app()) as c:
        yield c


def test_plotly_is_compressed_cached_and_revalidated(client):
    response = client.get("/vendor/plotly.min.js", headers={"Accept-Encoding": "gzip"})
    assert response.status_code == 200
    assert response.headers["content-encoding"] == "gzip"
    assert int(response.headers["content-length"]) < 0.4 * PLOTLY_JS.stat().st_size
    assert response.content == PLOTLY_JS.read_bytes()  # httpx decodes the gzip body
    # the partial bundle: a third of the full build's 4.8 MB, under 0.4 MB on the wire
    assert PLOTLY_JS.stat().st_size < 1.3e6 and int(response.headers["content-length"]) < 4e5
    assert "max-age=604800" in response.headers["cache-control"]
    etag = response.headers["etag"]
    again = client.get("/vendor/plotly.min.js", headers={"If-None-Match": etag})
    assert again.status_code == 304 and again.content == b""
    plain = client.get("/vendor/plotly.min.js", headers={"Accept-Encoding": "identity"})
    assert "content-encoding" not in plain.headers
    assert plain.content == PLOTLY_JS.read_bytes()


@pytest.mark.parametrize("path", ["/", "/js/main.js", "/css/explorer.css"])
def test_the_page_files_are_gzipped(client, path):
    response = client.get(path, headers={"Accept-Encoding": "gzip"})
    assert response.status_code == 200
    assert response.headers.get("content-encoding") == "gzip"


def test_api_answers_are_not_compressed(client):
    response = client.post("/api/explore", json={}, headers={"Accept-Encoding": "gzip"})
    assert response.status_code == 200
    assert "content-encoding" not in response.headers


def test_busy_fit_workers_answer_429_with_retry_after_before_reading(client, monkeypatch):
    jobs = client.app.state.fit_workers
    monkeypatch.setattr(jobs, "full", lambda: True)
    response = client.post("/api/fit/jobs", files={"file": ("x.csv", b"not even a csv")})
    assert response.status_code == 429
    assert response.headers["retry-after"] == "5"
    assert response.json()["detail"][0]["type"] == "busy"
    assert "busy" in response.json()["detail"][0]["msg"]


def test_an_internal_error_is_a_422_without_exception_text(client, monkeypatch):
    from breakaway.api.routers import explore

    def broken(*args, **kwargs):
        raise ZeroDivisionError("float division by zero in frame")

    monkeypatch.setattr(explore, "explore_frame", broken)
    response = client.post("/api/explore", json={})
    assert response.status_code == 422
    text = response.text
    assert "ZeroDivisionError" not in text and "division" not in text
    assert "cannot evaluate" in text


def test_only_allowed_hosts_are_answered(client, monkeypatch):
    from breakaway.settings import Settings

    assert Settings(allowed_hosts="localhost,127.0.0.1,[::1]").host_allowed("127.0.0.1:8000")
    assert Settings(allowed_hosts="localhost,[::1]").host_allowed("[::1]:8000")
    assert not Settings(allowed_hosts="localhost").host_allowed("evil.example:8000")
    assert Settings(allowed_hosts="*").host_allowed("anything")
    response = client.get("/api/health", headers={"Host": "rebound.example"})
    assert response.status_code == 400
    assert response.json()["detail"][0]["loc"] == ["header", "host"]


def test_cross_site_posts_are_refused_and_same_site_ones_pass(client):
    files = {"file": ("x.csv", b"v,F\n" + b"".join(b"%d,%d\n" % (i + 1, i + 1) for i in range(12)))}
    evil = client.post("/api/fit/jobs", files=files, headers={"Origin": "https://evil.example"})
    assert evil.status_code == 403
    assert evil.json()["detail"][0]["loc"] == ["header", "origin"]
    assert "content-security-policy" in evil.headers
    same = client.post("/api/explore", json={}, headers={"Origin": "http://testserver"})
    assert same.status_code == 200
    plain = client.post("/api/explore", json={})  # scripts send no Origin
    assert plain.status_code == 200
    assert client.get("/api/health", headers={"Origin": "https://evil.example"}).status_code == 200


def test_a_null_origin_is_refused_like_another_site(client):
    # a sandboxed frame of any site sends "Origin: null"
    response = client.post("/api/explore", json={}, headers={"Origin": "null"})
    assert response.status_code == 403
    assert response.json()["detail"][0]["loc"] == ["header", "origin"]


def test_cors_is_off_unless_configured(client, make_client):
    preflight = {"Origin": "https://course.example", "Access-Control-Request-Method": "POST"}
    off = client.options("/api/explore", headers=preflight)
    assert "access-control-allow-origin" not in off.headers
    assert client.post("/api/explore", json={},
                       headers={"Origin": "https://course.example"}).status_code == 403
    with make_client(cors_origins="https://course.example") as allowed:
        on = allowed.options("/api/explore", headers=preflight)
        assert on.headers["access-control-allow-origin"] == "https://course.example"
        answer = allowed.post("/api/explore", json={},
                              headers={"Origin": "https://course.example"})
        assert answer.status_code == 200
        assert answer.headers["access-control-allow-origin"] == "https://course.example"
        assert allowed.post("/api/explore", json={},
                            headers={"Origin": "https://evil.example"}).status_code == 403
