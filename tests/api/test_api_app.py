"""Health, presets, the served frontend, Plotly, docs, and the security headers."""

from __future__ import annotations

import os

import re

import pytest

from breakaway import __version__
from breakaway.api.routers.assets import PLOTLY_BUNDLE
from breakaway.params import DEFAULTS, LUGRE_1995, PRESET_DESCRIPTIONS, PRESETS
from breakaway.settings import get_settings

FRONTEND = get_settings().frontend_dir


def test_health(client):
    response = client.get("/api/health")
    assert response.status_code == 200
    assert response.json() == {"status": "ok", "version": __version__, "worker": os.getpid()}


def test_presets_list_every_preset_with_its_parameters(client):
    body = client.get("/api/presets").json()
    assert [p["name"] for p in body["presets"]] == list(PRESETS)
    for preset in body["presets"]:
        assert preset["params"] == PRESETS[preset["name"]]
        assert preset["description"] == PRESET_DESCRIPTIONS[preset["name"]]
    assert body["defaults"] == DEFAULTS
    assert body["lugre_1995"] == pytest.approx(LUGRE_1995, rel=0)
    assert {"fig5", "lugre-1995"} <= {p["name"] for p in body["presets"]}


def test_frontend_is_served_at_root(client):
    response = client.get("/")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    assert response.text == (FRONTEND / "index.html").read_text()
    assert client.get("/js/main.js").headers["content-type"].split(";")[0] in (
        "text/javascript", "application/javascript")


def test_frontend_has_no_inline_script_or_handler():
    for page in FRONTEND.rglob("*.html"):
        html = page.read_text()
        for tag in re.findall(r"<script\b[^>]*>(.*?)</script>", html, flags=re.S):
            assert tag.strip() == "", f"inline script in {page}"
        assert not re.search(r"\son[a-z]+\s*=", html), f"inline event handler in {page}"


def test_plotly_is_served_from_the_vendored_bundle(client):
    response = client.get("/vendor/plotly.min.js")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/javascript")
    assert response.content == (FRONTEND / PLOTLY_BUNDLE).read_bytes()
    assert (FRONTEND / "vendor" / "LICENSE-plotly.js.txt").read_text().startswith("MIT License")
    html = client.get("/").text
    assert 'src="/vendor/plotly.min.js"' in html
    assert "cdn" not in html.lower()


def test_openapi_and_docs(client):
    schema = client.get("/openapi.json").json()
    for path in ("/api/explore", "/api/simulate", "/api/presets", "/api/health"):
        assert path in schema["paths"]
    assert "ExploreRequest" in schema["components"]["schemas"]
    docs = client.get("/docs")
    assert docs.status_code == 200
    assert "swagger-ui" in docs.text
    scripts = re.findall(r"<script\b([^>]*)>(.*?)</script>", docs.text, flags=re.S)
    assert scripts and all("src=" in attrs and body.strip() == "" for attrs, body in scripts)
    assert client.get("/docs/init.js").status_code == 200
    # offline: every script and stylesheet of the docs page is served by this app
    assets = re.findall(r'(?:src|href)="([^"]+\.(?:js|css))"', docs.text)
    assert sorted(assets) == ["/docs/init.js", "/vendor/swagger-ui/swagger-ui-bundle.js",
                              "/vendor/swagger-ui/swagger-ui.css"]
    for asset in assets:
        response = client.get(asset)
        assert response.status_code == 200 and len(response.content) > 1000 or asset.endswith("init.js")
    assert "cdn" not in docs.text.lower()
    assert "cdn" not in docs.headers["content-security-policy"]
    assert client.get("/vendor/swagger-ui/index.html").status_code == 404


@pytest.mark.parametrize(("method", "path", "body"), [
    ("get", "/", None),
    ("get", "/api/health", None),
    ("get", "/api/presets", None),
    ("post", "/api/explore", {}),
    ("post", "/api/explore", {"Fc": -1}),  # 422
    ("get", "/no/such/page", None),  # 404
    ("get", "/vendor/plotly.min.js", None),
    ("get", "/docs", None),
])
def test_security_headers_on_every_response(client, method, path, body):
    kwargs = {"json": body} if body is not None else {}
    response = getattr(client, method)(path, headers={"Origin": "https://evil.example"}, **kwargs)
    headers = response.headers
    assert headers["x-content-type-options"] == "nosniff"
    csp = headers["content-security-policy"]
    script_src = re.search(r"script-src ([^;]*)", csp).group(1)
    assert "'unsafe-inline'" not in script_src and "'unsafe-eval'" not in script_src
    assert "default-src 'self'" in csp
    assert "access-control-allow-origin" not in headers


def test_no_cors_preflight(client):
    response = client.options("/api/explore", headers={
        "Origin": "https://evil.example", "Access-Control-Request-Method": "POST"})
    assert response.status_code in (404, 405)
    assert "access-control-allow-origin" not in response.headers


def test_presets_serve_the_one_parameter_table(client):
    from breakaway.params import CONTROLS, NORMALISED_PRESETS

    body = client.get("/api/presets").json()
    assert [row["name"] for row in body["parameters"]] == [row["name"] for row in CONTROLS]
    for row, served in zip(CONTROLS, body["parameters"]):
        for key, value in row.items():
            assert served[key] == value, (row["name"], key)
    units = {p["name"]: p["units"] for p in body["presets"]}
    assert {n for n, u in units.items() if u == "normalised"} == set(NORMALISED_PRESETS)
    assert units["lab-stage"] == "SI"
