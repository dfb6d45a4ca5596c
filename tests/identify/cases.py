"""Seeded generators of the data classes on which the first engine was confidently
wrong (issue 9). Each returns a Dataset and what is true about it."""

from __future__ import annotations

import math

import numpy as np

from breakaway.identify.csvdata import Dataset
from breakaway.identify.models import problem_for
from breakaway.identify.synthetic import BASE_TRUTH, displacement_excitation, effect_truth


def dataset(kind, columns, meta=None) -> Dataset:
    n = len(next(iter(columns.values())))
    return Dataset(kind=kind, columns={k: np.asarray(v, float) for k, v in columns.items()},
                   meta=dict(meta or {}), n=n, ignored_columns=(), lines=np.arange(n) + 2)


def breakaway_force(k, params, s=1.0, direction=None, tau_det=0.0):
    """E13 (avg, z* = 0.95) through the engine's own forward model, plus a detection delay."""
    data = dataset("breakaway", {"k": k, "F_ba": np.zeros_like(k)}, {"s": str(s)})
    effects = ("detection",) if tau_det else ()
    return problem_for(data, effects).predict({**params, "tau_det": tau_det})


def repeated_breakaway(seed=0, rates=(0.5, 1.0, 2.0, 5.0, 10.0), repeats=10, noise=0.02,
                       resolution=0.01):
    """Break-away repeated at each rate; F_ba recorded to ``resolution`` (a display of
    two decimals), so neighbouring rows often read the same."""
    rng = np.random.default_rng(seed)
    k = np.repeat(np.asarray(rates, float), repeats)
    truth = BASE_TRUTH["breakaway"]
    clean = breakaway_force(k, truth)
    F = np.round((clean + noise * rng.standard_normal(k.size)) / resolution) * resolution
    return dataset("breakaway", {"k": k, "F_ba": F}, {"s": "1"}), {"noise": noise}


def single_rate_breakaway(seed=0, k=50.0, repeats=20, noise=0.02):
    rng = np.random.default_rng(seed)
    rates = np.full(repeats, k)
    clean = breakaway_force(rates, BASE_TRUTH["breakaway"])
    F = clean + noise * rng.standard_normal(repeats)
    return dataset("breakaway", {"k": rates, "F_ba": F}), {"level": float(clean[0])}


def detection_joint(seed=0, noise=0.05):
    """A robot joint whose break-away torque rises with the torque rate (3 → 5.2 N·m over
    50 → 250 N·m/s): motion is noticed τ_det late. No '# s:' line."""
    rng = np.random.default_rng(seed)
    k = np.repeat(np.linspace(50.0, 250.0, 9), 4)
    params = {"Fc": 2.2, "Fs": 2.6, "V": 400.0, "delta": 1.0}
    tau = 0.011
    F = breakaway_force(k, params, tau_det=tau) + noise * rng.standard_normal(k.size)
    return dataset("breakaway", {"k": k, "F_ba": F}, {"units": "rotary"}), {"tau_det": tau}


def _timeseries(x, t, params, effects=(), F_noise=0.05, seed=0, extra=None):
    rng = np.random.default_rng(seed + 1)
    skeleton = dataset("timeseries", {"t": t, "x": x, "F": np.zeros_like(t)})
    clean = problem_for(skeleton, effects).predict({**params, **(extra or {})})
    return clean + F_noise * rng.standard_normal(t.size)


def one_direction(seed=0, n=6000, F_noise=0.05):
    """A slow feed in one direction with stops (the force keeps its sign)."""
    rate = 1000.0
    t = np.arange(n) / rate
    speed = 0.004 * (1 + np.sin(2 * math.pi * t / 1.5)) ** 2 / 4
    x = np.cumsum(speed) / rate
    truth = BASE_TRUTH["timeseries"]
    F = _timeseries(x, t, truth, F_noise=F_noise, seed=seed)
    return dataset("timeseries", {"t": t, "x": x, "F": F}), truth


def encoder_record(seed=0, n=12_000, count=2e-6, F_noise=0.05):
    """Strokes read by an encoder of ``count`` m, with one count of jitter while at rest."""
    rng = np.random.default_rng(seed)
    t, x = displacement_excitation(rng, n)
    truth = BASE_TRUTH["timeseries"]
    F = _timeseries(x, t, truth, F_noise=F_noise, seed=seed)
    counts = np.round(x / count)
    at_rest = np.abs(np.gradient(x, t)) < 1e-4
    jitter = rng.integers(-1, 2, size=n) * (rng.random(n) < 0.3)
    counts = counts + np.where(at_rest, jitter, 0)
    return dataset("timeseries", {"t": t, "x": counts * count, "F": F}), {"count": count}


def force_command(seed=0, n=10_000, x_noise=2e-6, effect=None):
    """Force-controlled rig: F is the command (noise-free), the noise sits in x; with
    ``effect`` (a §7 name) in the force."""
    rng = np.random.default_rng(seed)
    t, x = displacement_excitation(rng, n)
    truth = dict(BASE_TRUTH["timeseries"])
    effects = (effect,) if effect else ()
    if effect:
        skeleton = dataset("timeseries", {"t": t, "x": x, "F": np.zeros_like(t)})
        truth.update(effect_truth("timeseries", effect, truth, problem_for(skeleton, effects)))
    F = _timeseries(x, t, truth, effects, F_noise=0.0)
    x_measured = x + x_noise * rng.standard_normal(n)
    return dataset("timeseries", {"t": t, "x": x_measured, "F": F}), truth


def long_ripple(seed=0, n=10_000):
    """A position dependence whose wavelength (3× the travel) the record cannot resolve."""
    rng = np.random.default_rng(seed)
    t, x = displacement_excitation(rng, n)
    truth = BASE_TRUTH["timeseries"]
    travel = float(np.ptp(x))
    F = _timeseries(x, t, truth, ("ripple",), seed=seed,
                    extra={"A": 0.6, "wavelength": 3 * travel, "phase": 0.4})
    return dataset("timeseries", {"t": t, "x": x, "F": F}), {"travel": travel}


def steady_with_rest_rows(seed=0):
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(1e-4, 0.05, 60)
    v = np.concatenate([-speeds[::-1], np.zeros(6), speeds])
    p = BASE_TRUTH["steady"]
    g = p["Fc"] + (p["Fs"] - p["Fc"]) * np.exp(-(np.abs(v) / p["V"]) ** p["delta"])
    F = np.sign(v) * g + 0.05 * rng.standard_normal(v.size)
    F[v == 0] = rng.uniform(-12, 12, 6)  # whatever stiction held at rest
    return dataset("steady", {"v": v, "F": F}), {"rest": 6}


def strengthening_steady(seed=0):
    """Friction that rises with speed at low speed (no Stribeck fall at all)."""
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(1e-4, 0.05, 60)
    v = np.concatenate([-speeds[::-1], speeds])
    g = 10.0 + 3.0 * (1 - np.exp(-np.abs(v) / 0.004))
    F = np.sign(v) * g + 0.05 * rng.standard_normal(v.size)
    return dataset("steady", {"v": v, "F": F}), {}


def quadratic_drag(seed=0):
    """Steady friction with a quadratic drag c·v·|v|: ``viscous-power`` with n = 2."""
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(1e-4, 0.3, 80)
    v = np.concatenate([-speeds[::-1], speeds])
    p = BASE_TRUTH["steady"]
    g = p["Fc"] + (p["Fs"] - p["Fc"]) * np.exp(-(np.abs(v) / p["V"]) ** p["delta"])
    F = np.sign(v) * g + 60.0 * v * np.abs(v) + 0.05 * rng.standard_normal(v.size)
    return dataset("steady", {"v": v, "F": F}), {"sigma": 60.0, "n": 2.0}


def speed_hump(seed=0):
    """Steady friction with a hump around one speed (a resonance of the drive, say):
    outside the library, which has nothing that rises and falls again with speed."""
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(1e-4, 0.3, 80)
    v = np.concatenate([-speeds[::-1], speeds])
    p = BASE_TRUTH["steady"]
    g = p["Fc"] + (p["Fs"] - p["Fc"]) * np.exp(-(np.abs(v) / p["V"]) ** p["delta"])
    hump = 2.0 * np.exp(-((np.log(np.abs(v)) - np.log(0.03)) / 0.4) ** 2)
    F = np.sign(v) * (g + hump) + 0.05 * rng.standard_normal(v.size)
    return dataset("steady", {"v": v, "F": F}), {}
