"""POST /api/loop: the position loop of MODEL.md §5b through the whole app."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.loop import loop_experiment
from breakaway.params import DEFAULTS, LOOP_COMMON, LOOP_DEFAULTS


def test_defaults_hunt_and_match_the_model(client):
    response = client.post("/api/loop", json={})
    assert response.status_code == 200, response.text
    body = response.json()
    d = LOOP_DEFAULTS["presliding"]
    assert body["controller"] == {name: d[name] for name in ("Kp", "Ki", "Kd", "u_max")}
    assert body["reference"] == {"kind": "step", "h": d["h"], "w": d["w"], "f": d["f"]}
    assert body["params"]["m"] == d["m"] and body["params"]["Fs"] == DEFAULTS["Fs"]
    assert body["duration"] == LOOP_COMMON["duration"] and body["F_hat"] == "avg"
    direct = loop_experiment("presliding", body["params"], body["controller"],
                             body["reference"], body["duration"])
    n = direct["t"].size
    assert n >= LOOP_COMMON["points"] + len(direct["stick_phases"])  # grid and events
    for key in ("t", "r", "x", "v", "u", "F", "e"):
        assert len(body[key]) == n
        # float32 on the wire
        np.testing.assert_allclose(body[key], direct[key], rtol=1e-6, atol=1e-6)
    assert body["hunting"] == pytest.approx(direct["hunting"])
    assert body["rms_error"] == pytest.approx(direct["rms_error"], rel=1e-12)
    assert len(body["stick_phases"]) == len(direct["stick_phases"])
    for got, want in zip(body["stick_phases"], direct["stick_phases"]):
        assert got == pytest.approx(want)
    assert set(body["stick_phases"][0]) == {"t_start", "t_ba", "k", "u_ba", "E13", "u_start",
                                           "F_ba", "direction"}


def test_without_stiction_the_loop_settles(client):
    body = client.post("/api/loop", json={"Fs": 1.0}).json()
    assert body["hunting"] is None and body["runaway"] is False


def test_lugre_takes_its_own_defaults_and_z_ba(client):
    body = client.post("/api/loop", json={"model": "lugre", "z_ba": 0.9}).json()
    d = LOOP_DEFAULTS["lugre"]
    assert body["controller"]["Kp"] == d["Kp"] and body["reference"]["h"] == d["h"]
    assert body["params"]["z_ba"] == 0.9 and body["params"]["sigma0"] == 1e5
    assert body["compensation"]["params"]["V"] == body["params"]["vs"]
    assert body["hunting"] is not None


def test_request_fields_reach_the_run(client):
    payload = {"m": 2e-5, "controller": {"Ki": 5.0, "u_max": 2.0},
               "reference": {"kind": "sine", "h": 4.0, "f": 1.0}, "duration": 2.0,
               "points": 500, "F_hat": "self",
               "compensation": {"scale": 0.5, "params": {"Fc": 0.9}}}
    body = client.post("/api/loop", json=payload).json()
    assert body["controller"] == {"Kp": 0.03, "Ki": 5.0, "Kd": 0.003, "u_max": 2.0}
    assert body["compensation"] == {"scale": 0.5, "params": {"Fc": 0.9, "Fs": 1.5, "V": 100.0,
                                                             "delta": 1.0, "sigma": 0.0}}
    t = np.array(body["t"])
    assert t[-1] == pytest.approx(2.0) and np.count_nonzero(np.diff(t) > 1e-9) >= 499
    assert max(abs(u) for u in body["u"]) <= 2.0 * (1 + 1e-7)
    np.testing.assert_allclose(body["r"], 4.0 * np.sin(2 * np.pi * t), atol=1e-5)


@pytest.mark.parametrize("payload,loc", [
    ({"controller": {"Kp": -1}}, ["body", "controller", "Kp"]),
    ({"controller": {"u_max": 0}}, ["body", "controller", "u_max"]),
    ({"controller": {"Ki": "fast"}}, ["body", "controller", "Ki"]),
    ({"reference": {"kind": "square"}}, ["body", "reference", "kind"]),
    ({"reference": {"h": 0}}, ["body", "reference", "h"]),
    ({"reference": {"kind": "sine", "f": 1000}}, ["body", "reference", "f"]),
    ({"duration": 0}, ["body", "duration"]),
    ({"duration": 1e4}, ["body", "duration"]),
    ({"points": 5}, ["body", "points"]),
    ({"points": 10**6}, ["body", "points"]),
    ({"compensation": {"scale": -1}}, ["body", "compensation", "scale"]),
    ({"compensation": {"params": {"Fs": 0.5}}}, ["body", "compensation", "params", "Fs"]),
    ({"compensation": {"params": {"s": 2}}}, ["body", "compensation", "params", "s"]),
    ({"Fs": 0.5}, ["body", "Fs"]),
    ({"model": "lugre", "s": 2.0}, ["body", "s"]),
    ({"model": "presliding", "sigma0": 2.0}, ["body", "sigma0"]),
    ({"k": 1.0}, ["body", "k"]),
    ({"F_hat": "max"}, ["body", "F_hat"]),
])
def test_bad_input_is_a_422_naming_the_field(client, payload, loc):
    response = client.post("/api/loop", json=payload)
    assert response.status_code == 422, response.text
    assert response.json()["detail"][0]["loc"] == loc


def test_nan_is_a_422(client):
    response = client.post("/api/loop", content=b'{"controller": {"Kd": NaN}}',
                           headers={"content-type": "application/json"})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"][:3] == ["body", "controller", "Kd"]


@pytest.mark.parametrize("payload", [
    {"controller": {"Kp": 1e30, "Ki": 1e30, "Kd": 0}},  # spends its step budget at once
    {"controller": {"Kp": 0, "Ki": 0, "Kd": 0}},  # no control: the body never moves
    {"m": 1e-30, "controller": {"Kd": 1e30}},
    {"reference": {"kind": "ramp", "w": 1e30}},
    {"reference": {"kind": "sine", "h": 1e-30, "f": 40}},
    {"model": "lugre", "controller": {"Kp": 1e-30}, "duration": 60, "max_steps": 1000},
])
def test_extreme_values_answer_without_a_500(client, payload):
    response = client.post("/api/loop", json=payload)
    assert response.status_code in (200, 422), response.text
    if response.status_code == 200:
        body = response.json()
        assert len(body["t"]) == len(body["x"]) and body["t_end"] <= body["duration"]


def test_unstable_gains_report_a_runaway(client):
    # Kd·Kp < m·Ki: the linear loop is unstable
    body = client.post("/api/loop", json={"model": "lugre", "controller": {
        "Kp": 1e3, "Ki": 1e5, "Kd": 20.0}}).json()
    assert body["runaway"] is True and body["t_end"] < body["duration"]
    assert body["hunting"] is None
