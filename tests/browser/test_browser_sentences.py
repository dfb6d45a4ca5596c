"""The sentences under the ramp and under the control loop, over a grid of states that
holds every slider at both ends of its range: every number they quote is the run's, and
every reason they give holds in that state (frontend/js/ramp/ramp.js explainBreakaway,
frontend/js/loop/loopexplain.js explainLoop)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from breakaway.params import CONTROLS, DEFAULTS, LOOP_DEFAULTS
from breakaway.quasistatic import breakaway_velocity
from breakaway.ramp import ramp_experiment
from breakaway.steady import steady_state_force

pytestmark = pytest.mark.browser

FRICTION = ("Fc", "Fs", "V", "delta", "sigma", "s", "z_ba")
NOT_A_NUMBER = re.compile(r"–|NaN|undefined|Infinity|null")


def with_value(state: dict, name: str, value: float) -> dict:
    """`state` with `name` at `value`, Fs and Fc kept coupled as the sliders keep them."""
    out = {**state, name: value}
    if name == "Fc" and out["Fs"] < value:
        out["Fs"] = value
    if name == "Fs" and out["Fc"] > value:
        out["Fc"] = value
    return out


def slider_ends() -> list[dict]:
    """The defaults with one slider at one end of its range (δ's ends ±4 and the smallest
    |δ| it offers, 0.05), and the states the old sentences got wrong."""
    states = []
    for row in CONTROLS:
        low = 0.0 if row["scale"] == "log0" else row["min"]
        for value in (low, row["max"]):
            states.append(with_value(DEFAULTS, row["name"], value))
    states += [with_value(DEFAULTS, "delta", 0.05), with_value(DEFAULTS, "delta", -0.05),
               {**DEFAULTS, "k": 1e6}, {**DEFAULTS, "Fs": 1.0, "k": 1e6}, {**DEFAULTS, "Fs": 1.0},
               {**DEFAULTS, "k": 0.01, "m": 10.0}]
    return states


def numbers_after(text: str, label: str) -> list[float]:
    return [float(v) for v in re.findall(rf"{re.escape(label)}([-−]?[\d.]+(?:e[-+]?\d+)?)", text.replace("−", "-"))]


def three(value: float) -> float:
    return float(f"{value:.3g}")


RAMP_BODY = ("Fc", "Fs", "V", "delta", "sigma", "s", "z_ba", "m")


@pytest.fixture(scope="module")
def ramp_grid():
    out = []
    for state in slider_ends():
        params = {name: float(state[name]) for name in RAMP_BODY}
        answer = ramp_experiment("presliding", float(state["k"]), {**params, "F_hat": "avg"},
                                 max_steps=300_000)
        out.append(({**state, "F_hat": "avg"}, answer))
    return out


def test_the_ramps_sentence_is_true_in_every_state(explorer, ramp_grid):
    explorer.open("?sim=0")
    sentences = explorer.page.evaluate("""async (grid) => {
      const { explainBreakaway } = await import('/js/ramp/ramp.js');
      return grid.map(([state, ramp]) => explainBreakaway({ ...ramp, k: state.k }, state));
    }""", ramp_grid)
    for (state, ramp), said in zip(ramp_grid, sentences):
        where = f"{state} → {said}"
        assert not NOT_A_NUMBER.search(said), where
        assert numbers_after(said, "At k = ")[0] == three(state["k"]), where
        if ramp["u_ba"] is None:
            assert "did not break away" in said, where
            assert numbers_after(said, "E13 says ") == [three(ramp["E13"])], where
            continue
        assert numbers_after(said, "E13 with F̂ = avg says ") == [three(ramp["E13"])], where
        u, F, E13 = ramp["u_ba"], ramp["F_ba"], ramp["E13"]
        assert numbers_after(said, "breaks away at u = ") == [three(u)], where
        assert numbers_after(said, "friction ")[0] == three(F), where
        assert numbers_after(said, "m·ẍ = ") == [three(u - F)], where
        gap = (E13 - u) / u
        if abs(gap) <= 0.5:
            quoted = re.search(r", ([+−])([\d.]+) % from u_ba", said)
            assert quoted and float(quoted.group(2)) == float(f"{100 * abs(gap):.2g}"), where
            assert (quoted.group(1) == "+") == (gap >= 0), where
        elif gap > 0:
            quoted = re.search(r", ([\d.e+]+) times u_ba", said)
            assert quoted and float(quoted.group(1)) == float(f"{1 + gap:.2g}"), where
        else:
            quoted = re.search(r", 1/([\d.e+]+) of u_ba", said)
            assert quoted and float(quoted.group(1)) == float(f"{1 / (1 + gap):.2g}"), where
        assert ("They agree" in said) == (abs(gap) < 0.01), where
        if "They agree" in said:
            continue
        # each reason the sentence gives is a fact of this run
        share = numbers_after(said, "m·ẍ is ")
        if share:
            assert share == [float(f"{100 * abs((u - F) / u):.2g}")], where
        v_ba = ramp["v"][int(np.argmin(np.abs(np.array(ramp["t"]) - ramp["t_ba"])))]
        if "the body reaches z* at ẋ = " in said:
            p = {name: float(state[name]) for name in FRICTION}
            assert numbers_after(said, "the body reaches z* at ẋ = ") == [three(v_ba)], where
            e12 = breakaway_velocity(state["k"], **p, F_hat="avg")
            assert numbers_after(said, "not at E12's ") == [three(float(e12))], where
            steady = steady_state_force(v_ba, p["Fc"], p["Fs"], p["V"], p["delta"], p["sigma"])
            assert numbers_after(said, "the steady friction there is ") == [three(float(steady))], where
        assert ("chattered through" in said) == (ramp["reversals"] > 0), where
        if ramp["reversals"]:
            assert numbers_after(said, "chattered through ") == [ramp["reversals"]], where
        weakening = state["Fs"] > state["Fc"] and state["delta"] > 0
        assert ("velocity weakening" in said) <= weakening, where
        assert said.count("They differ because") + said.count("chattered") >= 1, where


#: The loop's sliders at both ends of their ranges (the page's table, loopstate.js), with
#: the reference or the compensation or the limit that shows them.
LOOP_ENDS = [
    ("Kp", 1e-3, {}), ("Kp", 1.0, {}), ("Ki", 0.0, {}), ("Ki", 100.0, {}), ("Kd", 0.0, {}),
    ("Kd", 0.1, {}), ("m_loop", 1e-6, {}), ("m_loop", 1e-2, {}), ("h", 0.1, {}), ("h", 1000.0, {}),
    ("w", 0.1, {"ref": "ramp"}), ("w", 1000.0, {"ref": "ramp"}), ("f", 0.02, {"ref": "sine"}),
    ("f", 10.0, {"ref": "sine"}), ("c", 0.0, {"comp": "scaled", "ref": "sine"}),
    ("c", 2.0, {"comp": "scaled", "ref": "sine"}), ("u_max", 0.1, {"limit": True}),
    ("u_max", 100.0, {"limit": True}),
]


def loop_states() -> list[dict]:
    loop = LOOP_DEFAULTS["presliding"]
    base = {**{name: DEFAULTS[name] for name in FRICTION}, "F_hat": "avg",
            "Kp": loop["Kp"], "Ki": loop["Ki"], "Kd": loop["Kd"], "m_loop": loop["m"],
            "ref": "step", "h": loop["h"], "w": loop["w"], "f": loop["f"], "comp": "off", "c": 0.5,
            "limit": False, "u_max": 2.0, "comp_model": "plant",
            "cFc": None, "cFs": None, "cV": None, "cdelta": None, "csigma": None}
    states = [base, {**base, "ref": "sine", "comp": "exact"}, {**base, "ref": "ramp", "Ki": 0.0}]
    states += [{**base, **extra, name: value} for name, value, extra in LOOP_ENDS]
    for row in CONTROLS:
        if row["name"] in FRICTION:
            low = 0.0 if row["scale"] == "log0" else row["min"]
            states += [with_value(base, row["name"], value) for value in (low, row["max"])]
    return states


def test_the_loops_sentence_is_true_in_every_state(explorer):
    explorer.open("?sim=0")
    page = explorer.page
    page.set_default_timeout(240_000)
    results = page.evaluate("""async (states) => {
      const { loopExperiment } = await import('/js/models/loopmodel.js');
      const { loopBody, loopDuration } = await import('/js/loop/loopstate.js');
      const { explainLoop, summarise, whatIfStates } = await import('/js/loop/loopexplain.js');
      const defaults = { h: states[0].h, w: states[0].w, f: states[0].f, duration: loopDuration() };
      const run = async (state) => loopExperiment(loopBody(state), defaults, 400000)
        ?? (await fetch('/api/loop', { method: 'POST', headers: { 'Content-Type': 'application/json' },
          body: JSON.stringify(loopBody(state)) })).json();
      const out = [];
      for (const state of states) {
        const loop = await run(state);
        const variants = whatIfStates(state, loop);
        const summary = {};
        for (const [name, variant] of Object.entries(variants)) summary[name] = summarise(await run(variant));
        if (variants.kd) summary.kdValue = variants.kd.Kd;
        const said = explainLoop(loop, state, Object.keys(variants).length ? summary : null);
        const s = summarise(loop);
        out.push({ said, verdict: s.verdict, hunting: loop.hunting, runaway: loop.runaway,
          comp: summary.comp ?? null, own: s, phases: loop.stick_phases.length });
      }
      return out;
    }""", loop_states())
    for state, result in zip(loop_states(), results):
        said = result["said"]
        where = f"{ {k: v for k, v in state.items() if v is not None} } → {said}"
        assert not NOT_A_NUMBER.search(said.replace("unbounded at v = 0", "")), where
        assert ("The loop hunts" in said) == (result["verdict"] == "hunts"), where
        assert ("The loop settles" in said) == (result["verdict"] == "settles"), where
        assert ("The loop is unstable" in said) == bool(result["runaway"]), where
        if "a full cycle" in said:
            assert result["hunting"]["cycle"] is not None, where
        assert ("integral term" in said) <= (state["Ki"] > 0), where
        assert ("Without integral action" in said) <= (state["Ki"] == 0), where
        assert ("integral windup" in said) <= (state["Ki"] > 0 and state["limit"]), where
        assert ("friction falls towards Fc" in said) <= (state["Fs"] > state["Fc"] and state["delta"] > 0), where
        assert ("It settles because Fs = Fc" in said) <= (state["Fs"] == state["Fc"]), where
        assert ("force limit" in said) <= state["limit"], where
        if "Kd·Kp = " in said:
            assert result["runaway"] and state["Kd"] * state["Kp"] <= state["m_loop"] * state["Ki"], where
        if "it sticks and slips instead" in said:
            compensated = result["own"] if state["comp"] != "off" else result["comp"]
            assert compensated["verdict"] == "hunts" or compensated["late"] > 0, where
        # every length in metres, every force in newtons: the page's linear units
        for unit in re.findall(r"(?<![\w.])[-−]?\d[\d.]*(?:e[-+]?\d+)? ([A-Za-z%][\w·/()²]*)", said):
            unit = unit.rstrip(",.;:")
            while unit.count(")") > unit.count("("):
                unit = unit[:-1].rstrip(",.;:")
            if re.fullmatch(r"[Nmskgradeg·/()²Hz]+", unit):  # a unit, not a word ("break-aways")
                assert unit in {"m", "N", "s", "N/s", "N·s/m", "N/(m·s)", "N²·s/m²", "Hz"}, (unit, where)
