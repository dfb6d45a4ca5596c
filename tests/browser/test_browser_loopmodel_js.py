"""The position loop run in the page (frontend/js/models/loopmodel.js) against the server's
(breakaway.loop.loop_experiment on the body POST /api/loop takes), and the page's choice
between its own run and the server's."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.api.loop_schemas import LoopRequest
from breakaway.loop import loop_experiment

pytestmark = pytest.mark.browser

BASE = {"model": "presliding", "Fc": 1.0, "Fs": 1.5, "V": 100.0, "delta": 1.0, "sigma": 0.0,
        "s": 1.0, "z_ba": 0.95, "m": 1e-5, "F_hat": "avg", "points": 2000,
        "controller": {"Kp": 0.03, "Ki": 3.0, "Kd": 0.003, "u_max": None},
        "reference": {"kind": "step", "h": 10.0}, "compensation": {"scale": 0.0}}

#: The default step (hunting), more Kd (it stops hunting), a force limit, a ramp, a sine
#: with exact compensation by another model, and Fs = Fc (it settles).
CASES = [
    {},
    {"controller": {"Kp": 0.03, "Ki": 3.0, "Kd": 0.03, "u_max": None}},
    {"controller": {"Kp": 0.03, "Ki": 3.0, "Kd": 0.003, "u_max": 1.2}, "F_hat": "self"},
    {"reference": {"kind": "ramp", "w": 5.0}, "sigma": 0.002},
    {"reference": {"kind": "sine", "h": 10.0, "f": 0.5},
     "compensation": {"scale": 1.0, "params": {"Fc": 0.9, "Fs": 1.6, "V": 80.0, "delta": 2.0,
                                               "sigma": 0.0}}},
    {"Fs": 1.0},
]

#: The same steps in float64 on both sides; pow, exp and log may differ in the last bit
#: between numba's libm and V8, and each of the run's dozens of reversals carries that
#: on, as a tighter tolerance does on the server: the values agree to 1e-5 of their
#: scale or within three times the integrator's own error (the server's run against one
#: at rtol = 1e-9), the events' numbers to 1e-7 or three times the largest relative own
#: error of a series.
RTOL_SERIES = 1e-5
RTOL_EVENTS = 1e-7


def own_error(body: dict) -> dict:
    """Max |run − run at rtol = 1e-9| on the grid, per series, of the server's run."""
    from breakaway.dynamics import simulate_loop

    args = LoopRequest(**body).worker_args()
    kwargs = {key: args[key] for key in ("params", "controller", "reference", "duration",
                                         "compensation", "points")}
    usual, tight = simulate_loop(**kwargs), simulate_loop(**kwargs, rtol=1e-9)
    a, b = usual.code == 0, tight.code == 0
    return {name: float(np.max(np.abs(getattr(usual, name)[a] - getattr(tight, name)[b])))
            for name in ("t", "x", "u", "F", "e")}


def page_run(explorer, body: dict, max_steps: int | None = None):
    return explorer.page.evaluate(
        """async ([body, n]) => (await import('/js/models/loopmodel.js')).loopExperiment(
             body, {h: 10, w: 5, f: 0.5, duration: 5}, n ?? undefined)""", [body, max_steps])


def python_run(body: dict) -> dict:
    return loop_experiment(**LoopRequest(**body).worker_args())


@pytest.mark.parametrize("case", CASES, ids=[str(i) for i in range(len(CASES))])
def test_the_pages_loop_run_is_the_servers(explorer, case):
    explorer.open("?sim=0")
    body = {**BASE, **case}
    mine, theirs = page_run(explorer, body), python_run(body)
    own = own_error(body)
    events = max(RTOL_EVENTS, *(3 * own[name] / np.max(np.abs(theirs[name])) for name in own))
    assert len(mine["t"]) == len(theirs["t"])
    for name in ("t", "x", "u", "F", "e"):
        scale = np.max(np.abs(theirs[name]))
        np.testing.assert_allclose(mine[name], theirs[name], rtol=0,
                                   atol=max(RTOL_SERIES * scale, 3 * own[name]), err_msg=name)
    assert mine["runaway"] == theirs["runaway"] and mine["t_end"] == pytest.approx(theirs["t_end"])
    assert abs(mine["reversals"] - theirs["reversals"]) <= 1  # one chatter more or less
    assert mine["rms_error"] == pytest.approx(theirs["rms_error"], rel=events)
    assert len(mine["stick_phases"]) == len(theirs["stick_phases"])
    for ours, python in zip(mine["stick_phases"], theirs["stick_phases"]):
        assert ours["direction"] == python["direction"]
        for key in ("t_start", "t_ba", "u_ba", "F_ba", "k", "E13"):
            if python[key] is None:
                assert ours[key] is None, key
            else:
                assert ours[key] == pytest.approx(python[key], rel=events, abs=1e-12), key
    if theirs["hunting"] is None:
        assert mine["hunting"] is None
    else:
        for key in ("period", "amplitude", "count"):
            assert mine["hunting"][key] == pytest.approx(theirs["hunting"][key], rel=events)
    assert mine["controller"] == LoopRequest(**body).resolved_controller()


def test_a_long_run_or_a_bad_body_is_left_to_the_server(explorer):
    explorer.open("?sim=0")
    assert page_run(explorer, BASE, 1000) is None  # over the step budget
    assert page_run(explorer, {**BASE, "Fs": 0.5}) is None  # Fs < Fc: the server says so
    assert page_run(explorer, {**BASE, "model": "lugre"}) is None
    sine = {**BASE, "reference": {"kind": "sine", "h": 10.0, "f": 50.0}}  # 250 periods
    assert page_run(explorer, sine) is None


def test_the_loop_view_draws_from_the_pages_run_without_asking_the_server(explorer):
    asked = []
    explorer.page.on("request", lambda r: asked.append(r.url.rsplit("/", 1)[-1]))
    explorer.open("?sim=0")
    explorer.page.evaluate("window.breakaway.loopReady()")
    start = len(asked)  # the defaults' echo came with the page
    slider = explorer.page.get_by_label("Ki [N/(m·s)] slider", exact=True)
    slider.focus()
    slider.press("PageUp")
    shown = explorer.page.evaluate("window.breakaway.loopReady()")
    state = explorer.state()
    assert shown["controller"]["Ki"] == pytest.approx(state["Ki"])
    assert "loop" not in asked[start:]
    theirs = python_run({**BASE, "controller": {**BASE["controller"], "Ki": state["Ki"]}})
    assert shown["rms_error"] == pytest.approx(theirs["rms_error"], rel=RTOL_SERIES)
    sentence = explorer.page.locator("#loop-explain").inner_text()
    assert explorer.page.locator("#loop-explain").get_attribute("data-whatifs") == "done"
    assert sentence
