"""Seeded synthetic measurements of every kind, with any of the library's effects, for tests,
benchmarks and the explorer's "mystery" samples.

The data come from the same forward model the engine fits (:class:`Problem`), plus
white Gaussian noise; effects are switched on by name and are *not* declared in the
output (no metadata says which).
"""

from __future__ import annotations

import io
import math

import numpy as np
from scipy.signal import lfilter

from .csvdata import Dataset
from .models import Problem, problem_for

#: Base parameters per kind: a small actuator (N, m, s).
BASE_TRUTH = {
    "timeseries": {"Fc": 10.0, "Fs": 15.0, "V": 0.005, "delta": 1.5, "s": 2000.0},
    "steady": {"Fc": 10.0, "Fs": 15.0, "V": 0.005, "delta": 1.5},
    "breakaway": {"Fc": 1.0, "Fs": 1.5, "V": 50.0, "delta": 1.0},
}
#: Noise std per kind [N].
NOISE = {"timeseries": 0.05, "steady": 0.05, "breakaway": 0.005}


def effect_truth(kind: str, effect: str, base: dict, problem: Problem | None = None) -> dict:
    """Clearly visible (several times the noise), physically plausible effect values."""
    Fc, Fs = base["Fc"], base["Fs"]
    if effect == "viscous":
        speed = problem.scales.speed if problem is not None else 1.0
        return {"sigma": 0.2 * Fc / speed}
    if effect == "viscous-power":
        # a curve well away from n = 1, as strong at the speed scale as the viscous case
        speed = problem.scales.speed if problem is not None else 1.0
        return {"sigma": 0.4 * Fc / speed**0.5, "n": 0.5}
    if effect == "asymmetry":
        # a different scale per direction (a pure shift of both levels would be an offset)
        return {"Fc_neg": 0.8 * Fc, "Fs_neg": 0.7 * Fs}
    if effect == "offset":
        return {"F_offset": 0.06 * Fc}
    if effect == "drift":
        return {"alpha": 0.1 / problem.scales.duration}
    if effect == "inertia":
        if kind == "breakaway":
            k_max = float(np.max(problem.k))
            F_hat = Fc + (Fs - Fc) / 2
            per_kg = k_max**2 / (problem.s * F_hat**2 * 0.95 * (-math.log(0.95)) ** 3)
            return {"m_e": 0.08 * Fc / per_kg}
        return {"m_e": 0.06 * Fc / problem.scales.accel}
    if effect == "ripple":
        return {"A": 0.04 * Fc, "wavelength": problem.scales.travel / 7.3, "phase": 0.7}
    if effect == "lag":
        return {"tau": 0.08}
    if effect == "backlash":
        return {"play": 0.6 / base["s"]}
    if effect == "dwell":
        return {"zeta": 0.12, "tau_d": 2.0}
    if effect == "detection":
        # the measured break-away rises by 15 % of Fc over the rates: a late detection
        return {"tau_det": 0.15 * Fc / float(np.max(problem.k))}
    raise ValueError(f"unknown effect {effect!r}")


def displacement_excitation(rng, n, rate=1000.0, travel=0.01, speed=0.02, presliding=5e-4):
    """Half-cosine strokes between random turning points.

    Stroke lengths are drawn so that some reversals stay inside the presliding
    distance and most reach gross sliding; peak speeds span a decade below ``speed``.
    """
    t = np.arange(n) / rate
    x = np.empty(n)
    i, position = 0, 0.0
    direction = 1.0
    while i < n:
        if rng.random() < 0.2:
            stroke = presliding * rng.uniform(0.2, 0.9)
        else:
            stroke = travel * rng.uniform(0.15, 0.5)
        target = float(np.clip(position + direction * stroke, -travel / 2, travel / 2))
        if abs(target - position) < 0.1 * presliding:
            target = position - direction * stroke
        peak = speed * 10 ** rng.uniform(-1.0, 0.0)
        duration = math.pi / 2 * abs(target - position) / peak
        m = max(int(duration * rate), 4)
        phase = np.arange(1, m + 1) / m
        seg = position + (target - position) * 0.5 * (1 - np.cos(np.pi * phase))
        take = min(m, n - i)
        x[i:i + take] = seg[:take]
        i += take
        position = target
        direction = -np.sign(target - x[max(i - 2, 0)]) if take > 1 else -direction
    x[0] = 0.0
    return t, x


def _dataset(kind, columns, meta=None):
    n = len(next(iter(columns.values())))
    return Dataset(kind=kind, columns={k: np.asarray(v, float) for k, v in columns.items()},
                   meta=dict(meta or {}), n=n, ignored_columns=(),
                   lines=np.arange(n) + 2 + len(meta or {}))


def _skeleton(kind, rng, n):
    """The excitation/regressors of a dataset, with the measured F still empty."""
    if kind == "timeseries":
        n = n or 20_000
        t, x = displacement_excitation(rng, n)
        return _dataset(kind, {"t": t, "x": x, "F": np.zeros(n)})
    if kind == "steady":
        n = n or 160
        half = n // 2
        speeds = np.geomspace(1e-4, 0.05, half)
        v = np.concatenate([-speeds[::-1], speeds])
        return _dataset(kind, {"v": v, "F": np.zeros(v.size)})
    n = n or 120
    # log-spaced rates resolve the Stribeck fall, linear ones the high-rate trend
    levels = n // 4
    k = np.repeat(np.sort(np.concatenate([np.geomspace(0.01, 30.0, levels - levels // 2),
                                          np.linspace(2.0, 30.0, levels // 2)])), 4)
    direction = np.tile([1.0, -1.0], k.size // 2)
    # four dwell times over three decades, rotated so each meets both directions
    levels_of_dwell = np.array([0.2, 2.0, 20.0, 200.0])
    row, rate_level = np.arange(k.size) % 4, np.arange(k.size) // 4
    dwell = levels_of_dwell[(row + rate_level) % 4]
    return _dataset(kind, {"k": k, "F_ba": np.zeros(k.size), "direction": direction,
                           "dwell": dwell}, {"s": "1"})


def make_dataset(kind: str, effects=(), seed: int = 0, noise: float | None = None,
                 n: int | None = None, params: dict | None = None):
    """A synthetic measurement with ``effects`` present but undeclared.

    Parameters
    ----------
    kind : {'timeseries', 'steady', 'breakaway'}
    effects : sequence of str
        library effects to include in the data.
    seed : int
        Seed of the excitation and the noise.
    noise : float, optional
        Noise std [N]; :data:`NOISE` by default.
    n : int, optional
        Rows.
    params : dict, optional
        Overrides of the true parameters (base and effect keys).

    Returns
    -------
    dataset : Dataset
    truth : dict
        The parameters the data were made with (base and effect keys).
    """
    rng = np.random.default_rng(seed)
    skeleton = _skeleton(kind, rng, n)
    if "detection" in effects:
        # a rig that reports late has no known presliding scale: no '# s:' line
        skeleton = _dataset(kind, skeleton.columns)
    problem = problem_for(skeleton, tuple(effects))
    truth = dict(BASE_TRUTH[kind])
    for effect in effects:
        truth.update(effect_truth(kind, effect, truth, problem))
    truth.update(params or {})
    clean = problem.predict(truth)
    sigma = NOISE[kind] if noise is None else noise
    measured = clean + sigma * rng.standard_normal(clean.size)
    column = "F_ba" if kind == "breakaway" else "F"
    if kind == "breakaway":
        measured = np.abs(measured)
    columns = {**skeleton.columns, column: measured}
    return _dataset(kind, columns, skeleton.meta), truth


def make_filtered_channel(seed: int = 0, n: int | None = None, delay: float = 0.015,
                          time_constant: float = 0.02, noise: float | None = None) -> Dataset:
    """Base-model timeseries seen through a delayed, low-pass filtered force channel.

    An effect outside the effect library (a sensor's dynamics): the force is delayed by
    ``delay`` [s] and passed through a first-order low-pass of ``time_constant`` [s]
    before the noise is added.
    """
    data, _ = make_dataset("timeseries", (), seed=seed, noise=0.0, n=n)
    F = data.columns["F"]
    t = data.columns["t"]
    dt = float(t[1] - t[0])
    shift = max(int(round(delay / dt)), 1)
    delayed = np.concatenate([np.full(shift, F[0]), F[:-shift]])
    a = math.exp(-dt / time_constant)
    filtered = lfilter([1 - a], [1, -a], delayed, zi=[a * delayed[0]])[0]
    sigma = NOISE["timeseries"] if noise is None else noise
    noisy = filtered + sigma * np.random.default_rng(seed).standard_normal(F.size)
    return with_force(data, noisy)


def with_force(dataset: Dataset, force) -> Dataset:
    """The same dataset with another measured force column."""
    column = "F_ba" if dataset.kind == "breakaway" else "F"
    return _dataset(dataset.kind, {**dataset.columns, column: force}, dataset.meta)


def to_csv(dataset: Dataset, comment: str | None = None) -> str:
    """CSV text of a dataset, metadata lines first."""
    out = io.StringIO()
    if comment:
        out.write(f"# {comment}\n")
    for key, value in dataset.meta.items():
        out.write(f"# {key}: {value}\n")
    names = list(dataset.columns)
    out.write(",".join(names) + "\n")
    table = np.column_stack([dataset.columns[c] for c in names])
    np.savetxt(out, table, delimiter=",", fmt="%.10g")
    return out.getvalue()
