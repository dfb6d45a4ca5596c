"""Machine-like versions of issue 9's data classes (:mod:`tests.identify.cases` builds
them from the engine's own forward model): repeated break-away on a rig, a slow feed in
one direction, strokes with one §7 effect, and strokes with none, each recorded the way
a rig records (an encoder, a load cell through an ADC, printed decimals).

The time series are a tribometer-like rig: a position-controlled drive moves the body
along the strokes, and the load cell holds the stationary counter-body, so it measures
the friction (no inertial force of the moving part). The friction is the core's (E6')
along the true position (:func:`breakaway.presliding.presliding_force_from_target`).
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from breakaway.dynamics import simulate_breakaway
from breakaway.identify.synthetic import displacement_excitation
from breakaway.presliding import motion_direction, presliding_force_from_target
from breakaway.steady import stribeck_magnitude

from .expectations import Close, Expectation
from .machines import REST_SHARE, Recording
from .plant import csv_text, encoder_counts, quantise

#: A load cell of ±50 N read by a 16-bit ADC.
LOAD_CELL_STEP = 100.0 / 2**16


def _load_cell(rng, force, noise):
    return quantise(force + noise * rng.standard_normal(force.size), LOAD_CELL_STEP)


def _linear_encoder(rng, t, x):
    """A linear encoder of 0.5, 1 or 2 µm that flickers by a count at rest."""
    count = rng.choice([0.5e-6, 1e-6, 2e-6])
    v = np.gradient(x, t)
    at_rest = np.abs(v) < REST_SHARE * np.max(np.abs(v))
    return encoder_counts(x, count, rng, at_rest) * count, count


def _levels(rng):
    Fc = rng.uniform(8.0, 12.0)
    return {"Fc": Fc, "Fs": Fc * rng.uniform(1.3, 1.6), "V": rng.uniform(2e-3, 8e-3),
            "delta": rng.uniform(1.0, 2.0)}


def _timeseries_csv(t, x, F, source):
    return csv_text({"t": (t, "%.3f"), "x": (x, "%.7f"), "F": (F, "%.4f")}, {"source": source})


# ---------------------------------------------------------------------------------
# repeated break-away at one or two rates
# ---------------------------------------------------------------------------------


def breakaway_repeats(seed: int = 0, rates: int = 1) -> Recording:
    """Break-away torque of a joint measured 12–20 times at each of one or two torque
    rates (5–50 N·m/s), from the ramp experiment itself (E7 with the joint's inertia,
    :func:`breakaway.dynamics.simulate_breakaway`). Between repeats the surface
    scatters the friction levels by 2 %; the torque sensor adds 0.005 N·m; the log
    prints two decimals."""
    rng = np.random.default_rng(seed)
    Fc = rng.uniform(1.5, 3.0)
    Fs, V = Fc * rng.uniform(1.2, 1.5), rng.uniform(0.05, 0.2)
    delta, s, J = rng.uniform(1.0, 2.0), 1.0 / rng.uniform(5e-4, 2e-3), rng.uniform(2e-3, 1e-2)
    ks = np.round(np.sort(rng.uniform(5.0, 50.0, rates)) * 2) / 2
    k = np.repeat(ks, rng.integers(12, 21))
    rng.shuffle(k)
    scatter = 1.0 + 0.02 * rng.standard_normal(k.size)
    u_ba = np.array([simulate_breakaway([rate], Fc * a, Fs * a, V, delta, s=s, m=J).u_ba[0]
                     for rate, a in zip(k, scatter)])
    measured = u_ba + 0.005 * rng.standard_normal(k.size)
    spread = math.sqrt(np.mean([np.var(measured[k == r], ddof=1) for r in ks]))
    csv = csv_text({"k [N·m/s]": (k, "%.1f"), "F_ba [N·m]": (measured, "%.2f")},
                   {"source": "joint break-away, torque ramps"})
    level = float(np.mean(u_ba))
    truth = {"level": level, "spread": spread, "Fc": Fc, "Fs": Fs, "s": s, "m": J}
    expect = Expectation(
        warnings=(("single-rate", None),),
        determined={"Fs": True, "Fc": False, "V": False, "delta": False},
        close={"Fs": Close(level, rel=0.03, required=True)}, noise=(spread, 1.6),
        force_max=float(np.max(measured)))
    return Recording(f"breakaway-{rates}-rate{'s' if rates > 1 else ''}", seed, csv, truth,
                     expect, {"k": k, "u_ba": u_ba})


# ---------------------------------------------------------------------------------
# a slow feed in one direction
# ---------------------------------------------------------------------------------


def feed_one_direction(seed: int = 0, rows: int = 8000) -> Recording:
    """A slow feed in one direction that slows to a stop every 1.5–3 s (peak 2–10
    mm/s), read by a linear encoder that flickers at the stops."""
    rng = np.random.default_rng(seed)
    truth = {**_levels(rng), "s": 1.0 / rng.uniform(2e-4, 1e-3)}
    t = np.arange(rows) / 1000.0
    speed = rng.uniform(2e-3, 1e-2) * ((1 + np.sin(2 * math.pi * t / rng.uniform(1.5, 3.0)
                                                    + rng.uniform(0, 2 * math.pi))) / 2) ** 2
    x = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t))])
    g = stribeck_magnitude(np.gradient(x, t), truth["Fc"], truth["Fs"], truth["V"],
                           truth["delta"])
    friction = presliding_force_from_target(x, motion_direction(x) * g, truth["s"])
    noise = rng.uniform(0.02, 0.06)
    F = _load_cell(rng, friction, noise)
    recorded, count = _linear_encoder(rng, t, x)
    expect = Expectation(
        warnings=(("one-direction", None), ("quantised", "x")),
        close={"Fc": Close(truth["Fc"]), "Fs": Close(truth["Fs"])},
        refused={"offset": "one-direction", "asymmetry": "one-direction"},
        force_max=float(np.max(np.abs(F))), speed_max=float(np.max(speed)))
    return Recording("feed-one-direction", seed, _timeseries_csv(
        t, recorded, F, "slow feed, linear encoder, load cell"),
        {**truth, "count": count, "noise": noise},
        expect, {"t": t, "x": x, "friction": friction})


# ---------------------------------------------------------------------------------
# strokes with one effect, or none
# ---------------------------------------------------------------------------------

#: The speed scale of the strokes [m/s] (:func:`displacement_excitation`).
STROKE_SPEED = 0.02


def strokes(seed: int = 0, effect: str | None = None, rows: int = 10_000) -> Recording:
    """Strokes back and forth of different lengths and speeds (up to 20 mm/s over a
    10 mm travel, some inside presliding), read by a linear encoder, with one §7
    effect in the friction: ``viscous`` (σ·v of 15–30 % of Fc at the top speed),
    ``offset`` (a load cell bias of ±4–8 % of Fc), ``drift`` (the levels change by
    ±5–15 % over the record) or none."""
    rng = np.random.default_rng(seed)
    truth = {**_levels(rng), "s": 1.0 / rng.uniform(3e-4, 8e-4)}
    t, x = displacement_excitation(rng, rows, presliding=1.0 / truth["s"])
    v = np.gradient(x, t)
    extra = {}
    if effect == "viscous":
        extra = {"sigma": rng.uniform(0.15, 0.3) * truth["Fc"] / STROKE_SPEED}
    elif effect == "offset":
        extra = {"F_offset": rng.choice([-1.0, 1.0]) * rng.uniform(0.04, 0.08) * truth["Fc"]}
    elif effect == "drift":
        extra = {"alpha": rng.choice([-1.0, 1.0]) * rng.uniform(0.05, 0.15) / (t[-1] - t[0])}
    elif effect is not None:
        raise ValueError(f"no stroke family with {effect!r}")
    g = stribeck_magnitude(v, truth["Fc"], truth["Fs"], truth["V"], truth["delta"])
    g = g * (1.0 + extra.get("alpha", 0.0) * (t - t[0]))
    target = motion_direction(x) * g + extra.get("sigma", 0.0) * v
    friction = presliding_force_from_target(x, target, truth["s"]) + extra.get("F_offset", 0.0)
    noise = rng.uniform(0.03, 0.08)
    F = _load_cell(rng, friction, noise)
    recorded, count = _linear_encoder(rng, t, x)
    named = frozenset({effect} if effect else ())
    close = {"Fc": Close(truth["Fc"]), "Fs": Close(truth["Fs"])}
    # the effect must be named; its value counts where the report determines it (strokes
    # whose Stribeck fall reaches their top speeds confound σ with Fc and V)
    close.update({k: Close(value) for k, value in extra.items()})
    expect = Expectation(
        required=named, allowed=named, warnings=(("quantised", "x"),), close=close,
        unexplained=None if effect else False,
        force_max=float(np.max(np.abs(F))), speed_max=float(np.max(np.abs(v))))
    return Recording(f"strokes-{effect or 'none'}", seed, _timeseries_csv(
        t, recorded, F, "strokes, linear encoder, load cell"),
        {**truth, **extra, "count": count, "noise": noise},
        expect, {"t": t, "x": x, "v": v, "friction": friction})


FAMILIES = {
    "breakaway-1-rate": partial(breakaway_repeats, rates=1),
    "breakaway-2-rates": partial(breakaway_repeats, rates=2),
    "feed-one-direction": feed_one_direction,
    "strokes-viscous": partial(strokes, effect="viscous"),
    "strokes-offset": partial(strokes, effect="offset"),
    "strokes-drift": partial(strokes, effect="drift"),
    "strokes-none": strokes,
}
