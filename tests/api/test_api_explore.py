"""POST /api/explore: the §9 contract, values against the model functions, 422s."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from breakaway.frame import FRAME_GRID, breakaway_curves, explore_frame, stribeck_curve
from breakaway.params import DEFAULTS, FIG3_RATES, PRESETS
from breakaway.presliding import hysteresis_loop
from breakaway.quasistatic import breakaway_force, phase_family, presliding_velocity
from breakaway.steady import steady_state_force

#: The payload carries float32 (relative error <= 6e-8) or 7 significant digits (<= 5e-7).
RTOL = 1e-6
PAYLOAD_LIMIT = 150 * 1024


def post(client, body):
    return client.post("/api/explore", json=body)


def close(actual, expected, rtol=RTOL):
    actual = np.asarray([np.nan if a is None else a for a in actual], dtype=float)
    np.testing.assert_allclose(actual, np.asarray(expected, dtype=float), rtol=rtol, atol=0)


def test_contract_fields_and_sizes(client):
    response = post(client, {})
    assert response.status_code == 200
    assert response.headers["content-type"] == "application/json"
    frame = response.json()
    assert set(frame) == {"stribeck", "hysteresis", "phase", "breakaway"}
    assert set(frame["stribeck"]) == {"v", "F"}
    assert set(frame["hysteresis"]) == {"x", "F"}
    assert set(frame["phase"]) == {"z", "curves"}
    assert set(frame["breakaway"]) == {"k", "Fc", "Fs", "avg", "self"}
    assert len(frame["stribeck"]["v"]) == len(frame["stribeck"]["F"]) == FRAME_GRID["stribeck"]
    assert len(frame["hysteresis"]["x"]) == len(frame["hysteresis"]["F"]) == FRAME_GRID["loop"]
    assert len(frame["phase"]["z"]) == FRAME_GRID["phase"]
    # the note's Fig. 3 family, then the current k
    rates = [curve["k"] for curve in frame["phase"]["curves"]]
    assert rates == pytest.approx(list(FIG3_RATES) + [DEFAULTS["k"]], rel=1e-12)
    assert all(len(curve["v"]) == FRAME_GRID["phase"] for curve in frame["phase"]["curves"])
    for name in ("k", "Fc", "Fs", "avg", "self"):
        assert len(frame["breakaway"][name]) == FRAME_GRID["breakaway"]


def test_defaults_match_the_model_functions(client):
    frame = post(client, {}).json()
    p = DEFAULTS
    v, F = stribeck_curve(p["Fc"], p["Fs"], p["V"], p["delta"], p["sigma"], FRAME_GRID["stribeck"])
    close(frame["stribeck"]["v"], v)
    close(frame["stribeck"]["F"], F)
    # the plotted F at the plotted v is Fss(v) (E2), v rounded to 7 digits
    close(frame["stribeck"]["F"],
          steady_state_force(np.array(frame["stribeck"]["v"]), p["Fc"], p["Fs"], p["V"], p["delta"]),
          rtol=1e-5)
    x, F_loop = hysteresis_loop(p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"])
    close(frame["hysteresis"]["x"], x)
    close(frame["hysteresis"]["F"], F_loop)
    z, v_phase = phase_family(p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"], "avg",
                              list(FIG3_RATES) + [p["k"]], FRAME_GRID["phase"])
    close(frame["phase"]["z"], z)
    for curve, expected in zip(frame["phase"]["curves"], v_phase):
        close(curve["v"], expected)
    k = np.array(frame["breakaway"]["k"])
    for name in ("Fc", "Fs", "avg", "self"):
        close(frame["breakaway"][name],
              breakaway_force(k, p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"], name,
                              p["z_ba"]), rtol=1e-5)


@pytest.mark.parametrize("params", [
    {"Fc": 2.0, "Fs": 3.5, "V": 5.0, "delta": 2.0, "sigma": 0.05, "s": 10.0, "z_ba": 0.9,
     "k": 7.5, "F_hat": "self"},
    {"Fc": 0.3, "Fs": 0.3, "V": 0.01, "delta": -1.5, "sigma": 0.0, "s": 1e4, "z_ba": 0.5,
     "k": 0.02, "F_hat": "Fs"},
])
def test_parameters_reach_the_model(client, params):
    frame = post(client, params).json()
    expected = explore_frame({**DEFAULTS, **params})
    close(frame["stribeck"]["F"], expected["stribeck"]["F"])
    close(frame["hysteresis"]["F"], expected["hysteresis"]["F"])
    current = frame["phase"]["curves"][-1]
    assert current["k"] == params["k"]
    close(current["v"], presliding_velocity(expected["phase"]["z"], params["k"], params["Fc"],
                                            params["Fs"], params["V"], params["delta"],
                                            params["s"], params["sigma"], params["F_hat"]))
    k, curves = breakaway_curves(params["Fc"], params["Fs"], params["V"], params["delta"],
                                 params["s"], params["sigma"], params["z_ba"])
    for name, values in curves.items():
        close(frame["breakaway"][name], values)
    # Stribeck: at the fastest plotted velocity the curve is near Fc + σ·v
    v_max = frame["stribeck"]["v"][-1]
    assert v_max == pytest.approx(5 * params["V"], rel=1e-6)


def test_grid_sizes_can_be_chosen(client):
    frame = post(client, {"grid": {"stribeck": 50, "loop": 100, "phase": 20,
                                   "breakaway": 30}}).json()
    assert len(frame["stribeck"]["v"]) == 50
    assert len(frame["hysteresis"]["x"]) == 100
    assert len(frame["phase"]["z"]) == 20
    assert len(frame["breakaway"]["k"]) == 30


@pytest.mark.parametrize("preset", sorted(PRESETS))
def test_payload_under_150_kb(client, preset):
    body = {key: value for key, value in PRESETS[preset].items()}
    for F_hat in ("avg", "self"):
        response = post(client, {**body, "F_hat": F_hat})
        assert response.status_code == 200
        assert len(response.content) <= PAYLOAD_LIMIT


def _max_digits(text: str) -> int:
    numbers = [token for token in text.replace("[", ",").replace("]", ",").replace(":", ",")
               .split(",") if token and token[0] in "-0123456789"]
    return max(len(n.lstrip("-").split("e")[0].replace(".", "").strip("0")) for n in numbers)


def test_floats_go_as_float32_in_the_usual_range(client):
    text = post(client, {}).text
    assert _max_digits(text) <= 9  # shortest float32 repr
    frame, expected = json.loads(text), explore_frame({})
    # float32 rounding and its shortest repr: relative error <= 2**-24 each
    close(frame["hysteresis"]["F"], expected["hysteresis"]["F"], rtol=2**-23)
    close(frame["breakaway"]["self"], expected["breakaway"]["self"], rtol=2**-23)


def test_floats_outside_float32_range_are_rounded_to_seven_digits(client):
    params = {"V": 1e30}  # v grid up to 5e30
    text = post(client, params).text
    assert _max_digits(text) <= 7
    frame, expected = json.loads(text), explore_frame(params)
    close(frame["stribeck"]["v"], expected["stribeck"]["v"], rtol=5e-7)
    close(frame["stribeck"]["F"], expected["stribeck"]["F"], rtol=5e-7)


# ---------------------------------------------------------------------------------
# invalid input: 422 naming the field, never a 500
# ---------------------------------------------------------------------------------

BAD = [
    ({"Fc": 0}, "Fc"),
    ({"Fc": -1.0}, "Fc"),
    ({"Fs": 0.5}, "Fs"),  # Fs < Fc = 1
    ({"Fc": 2.0}, "Fs"),  # default Fs = 1.5 < Fc
    ({"V": 0}, "V"),
    ({"V": -3}, "V"),
    ({"delta": 0}, "delta"),
    ({"delta": 0.01}, "delta"),
    ({"delta": -0.049}, "delta"),
    ({"sigma": -0.1}, "sigma"),
    ({"s": 0}, "s"),
    ({"z_ba": 0}, "z_ba"),
    ({"z_ba": 1}, "z_ba"),
    ({"z_ba": 1.5}, "z_ba"),
    ({"m": 0}, "m"),
    ({"k": 0}, "k"),
    ({"k": -2}, "k"),
    ({"F_hat": "median"}, "F_hat"),
    ({"Fc": "1.0"}, "Fc"),  # strings are not numbers
    ({"Fc": True}, "Fc"),
    ({"V": None}, "V"),
    ({"k": [1, 2]}, "k"),
    ({"sigma": {"a": 1}}, "sigma"),
    ({"Fcc": 1.0}, "Fcc"),  # unknown field
    ({"grid": {"loop": 10**6}}, "loop"),
    ({"grid": {"stribeck": 5001}}, "stribeck"),
    ({"grid": {"phase": 2}}, "phase"),
    ({"grid": {"breakaway": 10.5}}, "breakaway"),
    ({"grid": {"mesh": 10}}, "mesh"),
]


@pytest.mark.parametrize(("body", "field"), BAD, ids=[repr(b) for b, _ in BAD])
def test_bad_values_get_422_naming_the_field(client, body, field):
    response = post(client, body)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"]
    assert any(error["loc"][-1] == field for error in detail), detail
    assert "content-security-policy" in response.headers


@pytest.mark.parametrize("literal", ["NaN", "Infinity", "-Infinity", "1e999"])
def test_non_finite_numbers_get_422(client, literal):
    response = client.post("/api/explore", content=f'{{"Fc": {literal}}}',
                           headers={"content-type": "application/json"})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == ["body", "Fc"]


@pytest.mark.parametrize("content", [b"", b"garbage", b"[1, 2]", b'"text"', b"null", b"{",
                                     b'{"Fc": 1, "Fc": }'])
def test_malformed_bodies_get_422(client, content):
    response = client.post("/api/explore", content=content,
                           headers={"content-type": "application/json"})
    assert response.status_code == 422, response.text


def test_a_body_that_is_not_text_gets_400(client):
    response = client.post("/api/explore", content=b"\xff\xfe\x00",
                           headers={"content-type": "application/json"})
    assert response.status_code == 400
    assert "detail" in response.json()


def test_body_over_the_cap_gets_413(client):
    body = b'{"Fc": 1.0, "pad": "' + b"x" * (70 * 1024) + b'"}'
    response = client.post("/api/explore", content=body,
                           headers={"content-type": "application/json"})
    assert response.status_code == 413
    assert response.json()["detail"][0]["type"] == "body_too_large"


def test_chunked_body_over_the_cap_gets_413(client):
    def chunks():
        yield b'{"pad": "'
        for _ in range(80):
            yield b"x" * 1024
        yield b'"}'

    response = client.post("/api/explore", content=chunks(),
                           headers={"content-type": "application/json"})
    assert response.status_code == 413


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # numpy overflow at the extremes
def test_garbage_never_gives_a_500(client):
    """Random fields with random JSON values, extremes inside §1 included."""
    rng = np.random.default_rng(20240611)
    fields = ["Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "m", "k", "F_hat", "grid", "x"]
    values = [0, -1, 1, 0.5, 1e-300, 1e300, 1e-12, 1e12, 0.999999999, 1e-9, -1e300, "", "1",
              None, True, [], {}, [1.0], {"loop": 10}, "avg", "self", 2**63, -0.05, 0.05,
              5e-324, 1.7976931348623157e308]
    for _ in range(400):
        body = {str(rng.choice(fields)): values[rng.integers(len(values))]
                for _ in range(rng.integers(1, 5))}
        response = post(client, body)
        assert response.status_code in (200, 422), (body, response.status_code, response.text)
        response.json()


@pytest.mark.parametrize("params", [
    {"Fc": 1e-300, "Fs": 1e300},
    {"V": 1e300, "s": 1e-300},
    {"V": 1e-300, "s": 1e300, "k": 1e300},
    {"delta": 1e6, "sigma": 1e300},
    {"delta": -1e6, "F_hat": "self", "k": 1e-300},
    {"z_ba": 1e-300, "F_hat": "self"},
    {"z_ba": 1 - 1e-16, "F_hat": "Fc"},
])
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
def test_extreme_values_inside_the_constraints_never_give_a_500(client, params):
    response = post(client, params)
    assert response.status_code in (200, 422), response.text
    body = response.json()
    if response.status_code == 200:
        assert set(body) == {"stribeck", "hysteresis", "phase", "breakaway"}
        assert all(value is None or math.isfinite(value) for value in body["stribeck"]["F"])
