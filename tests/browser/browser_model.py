"""What the model says each plot must show, from the model functions themselves."""

from __future__ import annotations

import numpy as np

from breakaway.params import DEFAULTS, FIG3_RATES
from breakaway.presliding import hysteresis_loop
from breakaway.quasistatic import breakaway_force, presliding_velocity
from breakaway.steady import steady_state_force

def until(page, predicate: str, seconds: float = 15.0) -> None:
    """Poll ``predicate`` (the page's CSP forbids wait_for_function's eval)."""
    for _ in range(int(seconds / 0.05)):
        if page.evaluate(predicate):
            return
        page.wait_for_timeout(50)
    raise AssertionError(f"not true within {seconds} s: {predicate}")


def wait_ready(page, signal: str = "ready") -> None:
    """Wait until the page's ``window.breakaway.<signal>()`` promise resolves.

    The hook is set when main.js has run; waiting for it first keeps a test from racing
    the module's start (``goto`` returning before the hook exists).
    """
    page.wait_for_function("() => window.breakaway !== undefined")
    page.evaluate(f"window.breakaway.{signal}()")


#: Plotted values carry float32 precision or 7 significant digits (relative error <= 5e-7).
RTOL = 1e-6


def values(seq) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in seq], dtype=float)


def close(actual, expected, rtol=RTOL) -> None:
    np.testing.assert_allclose(values(actual), np.asarray(expected, dtype=float), rtol=rtol,
                               atol=0)


def split_gaps(trace) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Curves of a trace whose curves are separated by nulls: (x, y, customdata k)."""
    curves, xs, ys, ks = [], [], [], []
    for x, y, k in zip(trace["x"], trace["y"], trace["customdata"] or [None] * len(trace["x"])):
        if x is None:
            curves.append((np.array(xs), values(ys), ks[0] if ks else None))
            xs, ys, ks = [], [], []
        else:
            xs.append(x)
            ys.append(y)
            ks.append(k)
    if xs:
        curves.append((np.array(xs), values(ys), ks[0]))
    return curves


def params_of(state: dict) -> dict:
    return {name: float(state[name]) if name != "F_hat" else state[name]
            for name in DEFAULTS}


def by_prefix(traces: dict, prefix: str) -> dict:
    matches = [trace for name, trace in traces.items() if name.startswith(prefix)]
    assert len(matches) == 1, (prefix, list(traces))
    return matches[0]


def assert_plots_match_model(explorer, state: dict | None = None) -> None:
    """Every plotted curve equals the model evaluated at the plotted abscissae."""
    state = explorer.state() if state is None else state
    p = params_of(state)
    Fc, Fs, V, delta, s, sigma = p["Fc"], p["Fs"], p["V"], p["delta"], p["s"], p["sigma"]

    stribeck = explorer.traces("stribeck")["Fss(v)"]
    v = values(stribeck["x"])
    assert v[0] == -v[-1] and abs(v[-1] / (5 * V) - 1) < RTOL  # the grid is [-5V, 5V]
    close(stribeck["y"], steady_state_force(v, Fc, Fs, V, delta, sigma), rtol=1e-5)

    hysteresis = explorer.traces("hysteresis")
    x, F = hysteresis_loop(Fc, Fs, V, delta, s, sigma)
    # the loop is drawn as two branches by direction of travel; together they hold
    # every sample of the model's loop (reversal points in both)
    drawn = []
    for name in ("moving +x", "moving −x"):
        xs, ys = values(hysteresis[name]["x"]), values(hysteresis[name]["y"])
        keep = np.isfinite(xs)
        drawn.append(np.column_stack([xs[keep], ys[keep]]))
    drawn = np.concatenate(drawn)
    model = np.column_stack([x, F])
    scale = np.abs(model).max(axis=0)
    gap = np.abs(model[:, None, :] - drawn[None, :, :]) / scale
    distance = gap.max(axis=2)
    assert distance.min(axis=1).max() < 1e-6  # every model sample is drawn
    assert distance.min(axis=0).max() < 1e-6  # and nothing else is

    phase = explorer.traces("phase")
    current = by_prefix(phase, "current k")
    z = values(current["x"])
    close(current["y"], presliding_velocity(np.linspace(0, 0.99, z.size), p["k"], Fc, Fs, V,
                                            delta, s, sigma, p["F_hat"]))
    family = split_gaps(by_prefix(phase, "k = 0.01"))
    assert [k for _, _, k in family] == list(FIG3_RATES)
    for (zs, vs, k) in family:
        close(vs, presliding_velocity(np.linspace(0, 0.99, zs.size), k, Fc, Fs, V, delta, s,
                                      sigma, p["F_hat"]))
    z_star = by_prefix(phase, "z* =")
    assert z_star["x"] == [p["z_ba"], p["z_ba"]]

    breakaway = explorer.traces("breakaway")
    for name in ("Fc", "Fs", "avg", "self"):
        curve = breakaway[f"F̂ = {name}"]
        k = values(curve["x"])
        close(curve["y"], breakaway_force(k, Fc, Fs, V, delta, s, sigma, name, p["z_ba"]),
              rtol=1e-5)
    marker = by_prefix(breakaway, "current k")
    assert marker["x"] == [p["k"]]
    chosen = breakaway[f"F̂ = {p['F_hat']}"]
    if chosen["x"][0] <= p["k"] <= chosen["x"][-1]:
        # the marker sits on the plotted curve (linear interpolation between grid points),
        # which is the model's F_ba(k) to the grid's interpolation error
        interpolated = np.interp(p["k"], chosen["x"], chosen["y"])
        assert abs(marker["y"][0] / interpolated - 1) < 1e-12
        expected = breakaway_force(p["k"], Fc, Fs, V, delta, s, sigma, p["F_hat"], p["z_ba"])
        assert abs(marker["y"][0] / expected - 1) < 5e-3
