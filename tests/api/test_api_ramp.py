"""POST /api/ramp: the ramp experiment at one rate, beside /api/simulate and E13."""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from breakaway.api.app import create_app
from breakaway.params import DEFAULTS
from breakaway.quasistatic import breakaway_force


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app()) as c:
        yield c


@pytest.mark.parametrize("k", [2.01, 10.0])
def test_ramp_breaks_away_where_simulate_does_and_gives_e13(client, k):
    ramp = client.post("/api/ramp", json={"k": k})
    assert ramp.status_code == 200, ramp.text
    body = ramp.json()
    simulated = client.post("/api/simulate", json={"k": [k]}).json()
    assert body["u_ba"] == pytest.approx(simulated["u_ba"][0], rel=1e-12)
    assert body["F_ba"] == pytest.approx(simulated["F_ba"][0], rel=1e-12)
    assert body["t_ba"] == pytest.approx(simulated["t_ba"][0], rel=1e-12)
    p = DEFAULTS
    e13 = float(breakaway_force(k, p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"],
                                p["F_hat"], p["z_ba"]))
    assert body["E13"] == pytest.approx(e13, rel=1e-12)
    explore = client.post("/api/explore", json={"k": k}).json()["breakaway"]
    on_grid = np.interp(k, explore["k"], explore[p["F_hat"]])
    assert body["E13"] == pytest.approx(on_grid, rel=0.01)
    t, u = np.array(body["t"]), np.array(body["u"])
    assert len(t) <= 2000 and np.all(np.diff(t) > 0)
    np.testing.assert_allclose(u, k * t, rtol=1e-12)
    assert t[-1] == pytest.approx(body["t_ba"], rel=1e-9)
    z = np.array(body["z"])
    assert z[-1] == pytest.approx(DEFAULTS["z_ba"], rel=1e-6)
    assert np.all(z >= 0)


def test_ramp_of_lugre(client):
    body = client.post("/api/ramp", json={"model": "lugre", "k": 5.0}).json()
    simulated = client.post("/api/simulate", json={"model": "lugre", "k": [5.0]}).json()
    assert body["F_ba"] == pytest.approx(simulated["F_ba"][0], rel=1e-12)
    assert max(body["F"]) == pytest.approx(body["F_ba"], rel=1e-3)


@pytest.mark.parametrize("payload,field", [
    ({"k": -1}, "k"), ({"k": [1, 2]}, "k"), ({"k": 1, "m": 0}, "m"),
    ({"k": 1, "Fs": 0.5}, "Fs"), ({"k": 1, "F_hat": "max"}, "F_hat"),
    ({"k": "fast"}, "k"), ({"k": 1, "sigma0": 3}, "sigma0"),
])
def test_bad_input_is_a_422_naming_the_field(client, payload, field):
    response = client.post("/api/ramp", json=payload)
    assert response.status_code == 422
    assert field in [str(part) for part in response.json()["detail"][0]["loc"]]
