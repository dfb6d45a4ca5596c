"""POST /api/simulate: values equal the model's simulations; 422s; the time budget."""

from __future__ import annotations

import asyncio

import numpy as np
import pytest

from breakaway.dynamics import simulate_breakaway, simulate_lugre_breakaway
from breakaway.params import DEFAULTS, LUGRE_1995

from coroutines import run_to_end

RATES = [0.5, 2.01, 10.0]


def simulate(client, body):
    return client.post("/api/simulate", json=body)


def as_array(values):
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def test_presliding_defaults_equal_the_model(client):
    response = simulate(client, {"k": RATES})
    assert response.status_code == 200, response.text
    result = response.json()
    assert set(result) == {"model", "k", "u_ba", "F_ba", "t_ba", "reversals", "params"}
    assert result["model"] == "presliding"
    p = {name: DEFAULTS[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba")}
    assert result["params"] == p
    expected = simulate_breakaway(RATES, **p, max_steps=1_000_000)
    # the same deterministic integrator in the worker process: identical to round-off
    np.testing.assert_allclose(result["k"], RATES, rtol=0)
    np.testing.assert_allclose(as_array(result["u_ba"]), expected.u_ba, rtol=1e-12)
    np.testing.assert_allclose(as_array(result["F_ba"]), expected.F_ba, rtol=1e-12)
    np.testing.assert_allclose(as_array(result["t_ba"]), expected.t_ba, rtol=1e-12)
    assert result["reversals"] == expected.reversals.tolist()
    # u_ba = k·t_ba (MODEL.md §5)
    np.testing.assert_allclose(as_array(result["u_ba"]), np.array(RATES) * as_array(result["t_ba"]),
                               rtol=1e-12)


def test_presliding_parameters_reach_the_model(client):
    body = {"k": [1.0, 5.0], "Fc": 0.8, "Fs": 1.1, "V": 3.0, "delta": 2.0, "sigma": 0.02,
            "s": 50.0, "m": 0.01, "z_ba": 0.9}
    result = simulate(client, body).json()
    params = {key: value for key, value in body.items() if key != "k"}
    expected = simulate_breakaway(body["k"], **params, max_steps=1_000_000)
    np.testing.assert_allclose(as_array(result["u_ba"]), expected.u_ba, rtol=1e-12)
    assert result["params"] == {**params}


def test_lugre_uses_the_1995_parameters_by_default(client):
    result = simulate(client, {"model": "lugre", "k": RATES}).json()
    assert result["model"] == "lugre"
    assert result["params"] == pytest.approx(LUGRE_1995, rel=0)
    expected = simulate_lugre_breakaway(RATES, max_steps=1_000_000)
    np.testing.assert_allclose(as_array(result["F_ba"]), expected.F_ba, rtol=1e-12)
    np.testing.assert_allclose(as_array(result["u_ba"]), expected.u_ba, rtol=1e-12)


def test_lugre_overrides_map_to_its_parameters(client):
    body = {"model": "lugre", "k": [2.0], "Fc": 0.9, "Fs": 1.2, "V": 0.002, "delta": 1.0,
            "sigma": 0.1, "m": 0.5, "sigma0": 2e4, "sigma1": 100.0}
    result = simulate(client, body).json()
    params = {"Fc": 0.9, "Fs": 1.2, "vs": 0.002, "delta": 1.0, "sigma2": 0.1, "m": 0.5,
              "sigma0": 2e4, "sigma1": 100.0}
    assert result["params"] == params
    expected = simulate_lugre_breakaway([2.0], params, max_steps=1_000_000)
    np.testing.assert_allclose(as_array(result["F_ba"]), expected.F_ba, rtol=1e-12)
    default = simulate(client, {"model": "lugre", "k": [2.0]}).json()
    assert default["F_ba"][0] != pytest.approx(result["F_ba"][0], rel=1e-3)


BAD = [
    ({"k": []}, "k"),
    ({"k": [1.0, 0.0]}, 1),
    ({"k": [-1.0]}, 0),
    ({"k": "1"}, "k"),
    ({"k": [1.0] * 65}, "k"),  # over settings.max_rates = 64
    ({}, "k"),
    ({"k": [1.0], "model": "coulomb"}, "model"),
    ({"k": [1.0], "Fc": 2.0}, "Fs"),
    ({"k": [1.0], "Fs": 0.5}, "Fs"),
    ({"k": [1.0], "V": 0}, "V"),
    ({"k": [1.0], "delta": 0}, "delta"),
    ({"k": [1.0], "sigma": -1}, "sigma"),
    ({"k": [1.0], "s": 0}, "s"),
    ({"k": [1.0], "z_ba": 1}, "z_ba"),
    ({"k": [1.0], "m": 0}, "m"),
    ({"k": [1.0], "sigma0": 1e5}, "sigma0"),  # LuGre only
    ({"k": [1.0], "model": "lugre", "s": 2.0}, "s"),  # presliding only
    ({"k": [1.0], "model": "lugre", "z_ba": 0.9}, "z_ba"),
    ({"k": [1.0], "model": "lugre", "sigma0": 0}, "sigma0"),
    ({"k": [1.0], "model": "lugre", "sigma1": -1}, "sigma1"),
    ({"k": [1.0], "F_hat": "avg"}, "F_hat"),  # not a simulation parameter
]


@pytest.mark.parametrize(("body", "field"), BAD, ids=[repr(b)[:60] for b, _ in BAD])
def test_bad_values_get_422_naming_the_field(client, body, field):
    response = simulate(client, body)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"]
    assert any(error["loc"][-1] == field for error in detail), detail


def test_nan_rate_gets_422(client):
    response = client.post("/api/simulate", content=b'{"k": [1.0, NaN]}',
                           headers={"content-type": "application/json"})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == ["body", "k", 1]


def test_a_rate_without_break_away_in_the_step_budget_is_null(make_client):
    with make_client(simulate_max_steps=50) as client:
        result = simulate(client, {"k": [1.0]}).json()
    assert result["u_ba"] == [None] and result["F_ba"] == [None] and result["t_ba"] == [None]


def test_over_the_time_budget_is_a_422_and_the_worker_recovers(make_client):
    # chattering at small rates with a tiny mass takes ~1 s: far over a 0.05 s budget
    slow = {"k": [0.01, 0.02, 0.03], "m": 1e-6}
    with make_client(simulate_timeout_s=0.05) as client:
        response = simulate(client, slow)
        assert response.status_code == 422
        error = response.json()["detail"][0]
        assert error["type"] == "simulation_timeout"
        assert error["loc"] == ["body", "k"]
        # the stuck worker was ended; the same runner starts a new one for the next run
        params = {name: DEFAULTS[name]
                  for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba")}
        result = run_to_end(client.app.state.simulations.run(
            60.0, "presliding", [1.0], params, 1_000_000))
    expected = simulate_breakaway([1.0], **params, max_steps=1_000_000)
    assert result["u_ba"][0] == pytest.approx(expected.u_ba[0], rel=1e-12)


def test_one_run_at_a_time_and_the_budget_counts_from_the_start_of_the_run():
    import time

    from breakaway.api.simulation import SimulationRunner, SimulationTimeout, SimulatorBusy

    runner = SimulationRunner()
    params = {name: DEFAULTS[name] for name in ("Fc", "Fs", "V", "delta", "sigma", "s", "m",
                                                  "z_ba")}

    async def scenario():
        # the first run holds the worker for 3 s (after the worker's start)
        first = asyncio.create_task(runner.run(60.0, 3.0, target=time.sleep))
        await asyncio.sleep(0.05)
        with pytest.raises(SimulatorBusy, match="busy for 0.2 s"):
            await runner.run(0.2, "presliding", [1.0], params, 1_000_000)
        # this one waits nearly 3 s for the worker, longer than its 2.5 s budget, and
        # still runs: the budget is the run's, from its start (the run itself takes
        # 0.1 s; the margin is for a loaded CI machine)
        loop = asyncio.get_running_loop()
        asked = loop.time()
        result = await runner.run(2.5, "presliding", [0.01], params, 1_000_000, wait=30.0)
        assert loop.time() - asked > 2.5
        await first
        # a run over its own budget is ended
        with pytest.raises(SimulationTimeout, match="longer than 0.5 s"):
            await runner.run(0.5, 3.0, target=time.sleep)
        # a full queue refuses at once: two wait behind a running one, the third is turned away
        runner._queue = 2
        holder = asyncio.create_task(runner.run(60.0, 1.0, target=time.sleep))
        await asyncio.sleep(0.05)
        waiters = [asyncio.create_task(runner.run(60.0, 0.01, target=time.sleep))
                   for _ in range(2)]
        await asyncio.sleep(0.05)
        asked = loop.time()
        with pytest.raises(SimulatorBusy, match="2 simulations are already waiting"):
            await runner.run(60.0, 0.01, target=time.sleep)
        assert loop.time() - asked < 0.1
        await asyncio.gather(holder, *waiters)
        return result

    try:
        result = run_to_end(scenario())
    finally:
        runner.shutdown()
    expected = simulate_breakaway([0.01], **params, max_steps=1_000_000)
    assert result["u_ba"][0] == pytest.approx(expected.u_ba[0], rel=1e-12)


def test_a_step_budget_bounds_the_wait(client):
    # a damper fitted in kN under the note's N/s rates: no rate breaks away quickly
    damper = {"Fc": 15430, "Fs": 16320, "V": 1.704e-4, "delta": 7.3, "s": 53.6}
    body = client.post("/api/simulate", json={"k": [0.01, 1.0], **damper,
                                              "max_steps": 20_000}).json()
    assert body["u_ba"] == [None, None]
    ok = client.post("/api/simulate", json={"k": [10.0], "max_steps": 20_000}).json()
    assert ok["u_ba"][0] is not None
    bad = client.post("/api/simulate", json={"k": [1.0], "max_steps": 10})
    assert bad.status_code == 422 and bad.json()["detail"][0]["loc"] == ["body", "max_steps"]
