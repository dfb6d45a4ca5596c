"""The ramp experiment run in the page (frontend/js/models/rampmodel.js) against the server's
(breakaway.ramp.ramp_experiment), and the page's choice between its own run and the
server's."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.params import DEFAULTS
from breakaway.ramp import ramp_experiment

pytestmark = pytest.mark.browser

NAMES = ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba", "F_hat")

#: Runs that stick without reversals (a heavy mass, a slow rate, a steep Stribeck fall,
#: viscous friction, a stage in SI units), and the default, which turns 8 times.
CASES = [
    {"m": 0.01},
    {"k": 0.05, "m": 0.01},
    {"delta": 3.0, "V": 0.5, "m": 0.05, "k": 0.2, "F_hat": "Fs"},
    {"k": 20.0, "m": 1e-3, "sigma": 0.5, "F_hat": "self"},
    {"Fc": 12.0, "Fs": 15.0, "V": 0.002, "delta": 0.7, "s": 2e5, "sigma": 40.0, "k": 300.0,
     "m": 2.0, "F_hat": "Fc"},
    {},
]

#: The same steps in float64 on both sides; pow, exp and log may differ in the last bit
#: between numba's libm and V8, and a reversal's bisection carries that on: 1e-7 of the
#: run over 8 reversals, 1e-12 without one.
RTOL_TURNS = 1e-7
RTOL_STRAIGHT = 1e-12


def body(case: dict) -> dict:
    return {**{name: DEFAULTS[name] for name in NAMES}, "k": DEFAULTS["k"], **case}


def page_run(explorer, params: dict, max_steps: int | None = None):
    return explorer.page.evaluate(
        """async ([p, n]) => (await import('/js/models/rampmodel.js')).rampExperiment(p, n ?? undefined)""",
        [params, max_steps])


def python_run(params: dict, rtol: float | None = None) -> dict:
    args = {name: params[name] for name in NAMES}
    if rtol is None:
        return ramp_experiment("presliding", params["k"], args, 300_000)
    from breakaway.dynamics import simulate_trajectory

    args.pop("F_hat")
    run = simulate_trajectory(params["k"], rtol=rtol, **args)
    return {"t_ba": run.t_ba, "F_ba": run.F_ba}


@pytest.mark.parametrize("case", CASES, ids=[str(i) for i in range(len(CASES))])
def test_the_pages_ramp_run_is_the_servers(explorer, case):
    explorer.open("?sim=0")
    params = body(case)
    mine, theirs = page_run(explorer, params), python_run(params)
    rtol = RTOL_TURNS if theirs["reversals"] else RTOL_STRAIGHT
    assert mine["reversals"] == theirs["reversals"]
    for name in ("t_ba", "u_ba", "F_ba"):
        assert mine[name] == pytest.approx(theirs[name], rel=rtol), name
    assert mine["E13"] == pytest.approx(theirs["E13"], rel=1e-12)
    if not theirs["reversals"]:  # the same steps: the same samples
        for name in ("t", "x", "v", "u", "F", "z"):
            np.testing.assert_allclose(mine[name], theirs[name], rtol=1e-10,
                                       atol=1e-10 * np.max(np.abs(theirs[name])), err_msg=name)
    else:  # F along the run, at the server's samples
        F = np.interp(theirs["t"], mine["t"], mine["F"])
        assert np.max(np.abs(F - theirs["F"])) <= 1e-5 * np.max(np.abs(theirs["F"]))


def test_a_chattering_run_agrees_within_the_integrators_own_error(explorer):
    # 150 reversals: each carries the last bit on, as a tighter tolerance does on the server
    explorer.open("?sim=0")
    params = body({"m": 1e-6})
    mine, theirs = page_run(explorer, params), python_run(params)
    tighter = python_run(params, rtol=1e-9)
    own_error = abs(theirs["t_ba"] - tighter["t_ba"])
    assert mine["reversals"] > 100
    assert abs(mine["t_ba"] - theirs["t_ba"]) <= 2 * own_error + 1e-9
    assert abs(mine["F_ba"] - tighter["F_ba"]) <= 0.01 * tighter["F_ba"]


def test_a_long_run_or_a_bad_body_is_left_to_the_server(explorer):
    explorer.open("?sim=0")
    assert page_run(explorer, body({"m": 1e-8})) is None  # 1716 reversals: too long
    assert page_run(explorer, body({"m": 1e-8}), 10_000_000)["reversals"] > 1000
    assert page_run(explorer, body({"Fs": 0.5})) is None  # Fs < Fc: the server says so
    assert page_run(explorer, body({"z_ba": 1.0})) is None


def test_a_mass_the_page_cannot_run_is_asked_of_the_server(explorer):
    asked = []
    explorer.page.on("request", lambda r: asked.append(r.url.rsplit("/", 1)[-1]))
    explorer.open("?sim=0&m=1e-8")
    view = explorer.page.evaluate("window.breakaway.viewParams('ramp')")
    assert view["m"] == pytest.approx(1e-8)
    assert "ramp" in asked
    shown = explorer.page.locator("#ba-explain").inner_text()
    server = ramp_experiment("presliding", DEFAULTS["k"],
                             {**{n: DEFAULTS[n] for n in NAMES}, "m": 1e-8}, 300_000)
    assert f"{server['reversals']} reversal" in shown
