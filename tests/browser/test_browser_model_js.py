"""The model's curves computed in the page (frontend/js/models/model.js) against the Python
model (breakaway.frame.explore_frame), for the frames drawn while a hand moves a slider."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.frame import explore_frame
from breakaway.params import DEFAULTS

pytestmark = pytest.mark.browser

#: Parameter sets that take each branch: the defaults, velocity strengthening (δ < 0),
#: viscous friction, a steep Stribeck fall where ẋ·Fss(ẋ) turns back (the self-consistent
#: root by bisection), a stage in SI units, Fs = Fc, and a Stribeck step (δ = 1000, where
#: (v/V)^δ overflows a float).
CASES = [
    {},
    {"delta": -1.5, "F_hat": "self"},
    {"sigma": 0.3, "F_hat": "Fs", "k": 7.5},
    {"Fc": 0.2, "Fs": 3.0, "delta": 4.0, "V": 2.0, "F_hat": "self", "z_ba": 0.6},
    {"Fc": 12.0, "Fs": 15.0, "V": 0.002, "delta": 0.7, "s": 2e5, "sigma": 40.0, "k": 300.0,
     "F_hat": "Fc"},
    {"Fc": 1.5, "Fs": 1.5, "F_hat": "self", "k": 0.03},
    {"delta": 1000.0, "V": 2.0, "F_hat": "self"},
]

#: Both sides evaluate the same formulas in the same order in float64; exp, log and pow
#: may differ in the last bit between numpy and V8, and Newton's last step by a few.
RTOL = 1e-12


def page_frame(explorer, params: dict) -> dict:
    return explorer.page.evaluate(
        """async (p) => (await import('/js/models/model.js')).modelFrame(p)""", params)


def assert_close(actual, expected, what: str) -> None:
    actual = np.asarray(actual, dtype=float)
    expected = np.asarray(expected, dtype=float)
    assert actual.shape == expected.shape, what
    scale = np.max(np.abs(expected[np.isfinite(expected)]), initial=0.0)
    np.testing.assert_allclose(actual, expected, rtol=RTOL, atol=RTOL * scale, err_msg=what)


@pytest.mark.parametrize("case", CASES, ids=[str(i) for i in range(len(CASES))])
def test_the_pages_frame_equals_the_servers_model(explorer, case):
    explorer.open("?sim=0")
    params = {**{k: v for k, v in DEFAULTS.items() if k != "m"}, **case}
    mine = page_frame(explorer, params)
    theirs = explore_frame(params)
    assert_close(mine["stribeck"]["v"], theirs["stribeck"]["v"], "stribeck v")
    assert_close(mine["stribeck"]["F"], theirs["stribeck"]["F"], "stribeck F")
    assert_close(mine["hysteresis"]["x"], theirs["hysteresis"]["x"], "loop x")
    assert_close(mine["hysteresis"]["F"], theirs["hysteresis"]["F"], "loop F")
    assert_close(mine["phase"]["z"], theirs["phase"]["z"], "phase z")
    assert [c["k"] for c in mine["phase"]["curves"]] == [c["k"] for c in theirs["phase"]["curves"]]
    for ours, python in zip(mine["phase"]["curves"], theirs["phase"]["curves"]):
        assert_close(ours["v"], python["v"], f"phase k={python['k']}")
    for name in ("k", "Fc", "Fs", "avg", "self"):
        assert_close(mine["breakaway"][name], theirs["breakaway"][name], f"breakaway {name}")


def test_the_pages_frame_equals_the_served_frame(explorer):
    # what the server sends is float32-rounded (api/encoding.py): within 6e-8
    explorer.open("?sim=0")
    params = {**{k: v for k, v in DEFAULTS.items() if k != "m"}, "F_hat": "self", "k": 3.3}
    served = explorer.page.evaluate(
        """async (p) => (await fetch('/api/explore', {method: 'POST', body: JSON.stringify(p),
            headers: {'Content-Type': 'application/json'}})).json()""", params)
    mine = page_frame(explorer, params)
    np.testing.assert_allclose(mine["hysteresis"]["F"], served["hysteresis"]["F"], rtol=1e-7,
                               atol=1e-7)
    np.testing.assert_allclose(mine["breakaway"]["self"], served["breakaway"]["self"], rtol=1e-7)
    np.testing.assert_allclose(mine["phase"]["curves"][-1]["v"],
                               served["phase"]["curves"][-1]["v"], rtol=1e-7)
