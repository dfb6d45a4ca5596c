"""The rig zoo (issue 26): seeded synthetic rigs that vary what real rigs vary, each with
what its report must say.

Every rig is physics first. A body moved by a stiff drive (a velocity loop, a hand, a
linear axis) follows its path and the friction along it is the core's (E6')
(:func:`breakaway.presliding.presliding_force_from_target`) with whatever the rig adds
to the target (a viscous term, straight or curved; a level that drifts with time or
varies with position). A body under a torque command is integrated with its friction
(:mod:`tests.identify.plant`). Only then is it recorded: an encoder's whole counts
(10 to 16,384 per revolution, logged in rad or degrees, or a linear scale), a force
sensor's noise, its ADC's steps, mains hum and spikes, or a force column that is a
command or a model-based estimate; then the decimals the logger prints.

Each seed draws every parameter from a plausible range, so the engine is scored on a
family, not a file; each :class:`~tests.identify.machines.Recording` carries its
:class:`~tests.identify.expectations.Expectation` (effects required and allowed,
warnings, parameters within tolerance where determined, the noise floor near the force
channel's own noise, ``input_floor`` present), the truth in the file's units, and the
hidden true signals the generator tests check. :func:`families` lists them by name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import PchipInterpolator

from breakaway.presliding import motion_direction, presliding_force_from_target
from breakaway.steady import stribeck_magnitude

from .expectations import Close, Expectation
from .machines import Recording
from .plant import (advance, csv_text, encoder_counts, friction_params, quantise,
                    rest_state, run_open_loop, substeps_for, S_F, S_V, S_X)

#: Counts per revolution of the rotary encoders a rig may carry.
ENCODER_COUNTS = (10, 16, 20, 32, 50, 64, 100, 128, 200, 256, 360, 500, 512, 1000, 1024,
                  2000, 2048, 2500, 4096, 8192, 16384)
#: Radians per degree: a file logged in degrees has V, s, σ and m_e per degree.
PER_DEGREE = math.pi / 180.0
#: Decimals a logger prints positions with, per unit.
POSITION_FORMAT = {"rad": "%.6f", "deg": "%.4f", "m": "%.7f"}
#: A column whose samples move by at most one count this often shows its steps.
VISIBLE_STEP_SHARE = 0.3
#: The share of critical presliding damping in an integrated plant: enough to settle a
#: branch, small enough that the damping force (outside the library) stays a few per
#: cent of Fc where a fast servo crosses presliding (it rings in reversals far below
#: one count instead).
PRESLIDING_DAMPING = 0.1


# ---------------------------------------------------------------------------------
# what the rig records
# ---------------------------------------------------------------------------------


@dataclass(frozen=True)
class Encoder:
    """A position channel: ``counts`` per revolution of a shaft turning ``per_turn``
    of travel per revolution (2π rad for a joint, a screw's lead or a pulley's
    circumference [m] for a linear axis), logged in ``unit`` ("rad", "deg" or "m")."""

    counts: int
    unit: str
    per_turn: float = 2 * math.pi

    @property
    def per_unit(self) -> float:
        """True travel per logged unit (rad per degree, else 1)."""
        return PER_DEGREE if self.unit == "deg" else 1.0

    @property
    def count(self) -> float:
        """One count in true travel [rad or m]."""
        return self.per_turn / self.counts

    @property
    def step(self) -> float:
        """One count in the logged unit."""
        return self.count / self.per_unit

    def record(self, x, rng, at_rest=None):
        """The logged reading of the true travel ``x`` (whole counts, in the unit) and
        the counts themselves."""
        counts = encoder_counts(x, self.count, rng, at_rest)
        return counts * self.step, counts

    def header(self) -> str:
        return f"x [{self.unit}]"


def rotary_encoder(rng, low=10, high=4096, degrees=0.5) -> Encoder:
    """A joint's encoder of ``low``–``high`` counts per revolution, logged in degrees
    with probability ``degrees``."""
    options = [c for c in ENCODER_COUNTS if low <= c <= high]
    return Encoder(int(rng.choice(options)), "deg" if rng.random() < degrees else "rad")


def linear_encoder(rng, belt=False) -> Encoder:
    """A linear scale of 1, 2 or 5 µm, or a motor encoder of 500–4096 counts on a screw
    of 5–20 mm lead (``belt``: on a pulley of 50–100 mm per turn, for fast axes)."""
    if rng.random() < 0.5:
        return Encoder(1, "m", float(rng.choice([1e-6, 2e-6, 5e-6])))
    counts = int(rng.choice([c for c in ENCODER_COUNTS if 500 <= c <= 4096]))
    turn = rng.choice([0.05, 0.075, 0.1]) if belt else rng.choice([5e-3, 10e-3, 20e-3])
    return Encoder(counts, "m", float(turn))


def steps_visible(counts) -> bool:
    """Whether a record moves by at most one count between samples often enough that
    its steps are plain to see (:data:`VISIBLE_STEP_SHARE`)."""
    moves = np.abs(np.diff(np.asarray(counts, float)))
    return bool(np.mean(moves <= 1) >= VISIBLE_STEP_SHARE)


@dataclass
class ForceChannel:
    """What a force sensor adds to the true force: white noise, mains hum, spikes, and
    its ADC's steps. ``parts`` keeps each one (the generator tests check them)."""

    noise: float
    step: float
    hum: float = 0.0
    hum_hz: float = 50.0
    spikes: int = 0
    spike_size: float = 0.0
    parts: dict = field(default_factory=dict, repr=False)

    def record(self, t, clean, rng):
        """The recorded force at times ``t`` of the true force ``clean``."""
        n = clean.size
        white = self.noise * rng.standard_normal(n)
        hum = self.hum * np.sin(2 * math.pi * self.hum_hz * t + rng.uniform(0, 2 * math.pi))
        spiked = np.zeros(n)
        rows = spike_rows(rng, n, self.spikes)
        spiked[rows] = self.spike_size * rng.choice([-1.0, 1.0], rows.size) \
            * rng.uniform(1.0, 2.0, rows.size)
        self.parts = {"white": white, "hum": hum, "spikes": spiked, "spike_rows": rows}
        return quantise(clean + white + hum + spiked, self.step)

    def floor(self) -> tuple[float, float]:
        """The noise floor a report must give: the white noise with the ADC's steps,
        within 1.5× either way; with hum, anywhere from the white noise alone to the
        white noise and the hum together (hum sampled a few times a period is as rough
        as noise; sampled finely it is a smooth unknown)."""
        white = math.hypot(self.noise, self.step / math.sqrt(12))
        if not self.hum:
            return white, 1.5
        low, high = white / 1.5, 1.5 * math.hypot(white, self.hum / math.sqrt(2))
        return math.sqrt(low * high), math.sqrt(high / low)


def spike_rows(rng, n, count, spacing=40):
    """``count`` isolated rows (at least ``spacing`` apart, away from the ends)."""
    if not count:
        return np.zeros(0, dtype=int)
    slots = rng.choice(n // spacing - 2, count, replace=False) + 1
    return np.sort(slots * spacing + rng.integers(0, spacing // 2, count))


def _sensor(rng, scale, noise_share=(0.005, 0.02), **disturbances) -> ForceChannel:
    """A force sensor on a rig whose friction is about ``scale``: noise a share of it,
    a 16-bit ADC over ±20 times it."""
    return ForceChannel(noise=rng.uniform(*noise_share) * scale,
                        step=40.0 * scale / 2**16, **disturbances)


def _hum(rng, noise):
    """Mains hum of 2–6 times the sensor's ``noise`` at 50 or 60 Hz."""
    return {"hum": rng.uniform(2.0, 6.0) * noise, "hum_hz": float(rng.choice([50.0, 60.0]))}


def _spikes(rng, scale):
    """5–30 spikes of 20–120 % of ``scale`` (a level of the friction)."""
    return {"spikes": int(rng.integers(5, 31)), "spike_size": rng.uniform(0.2, 0.6) * scale}


# ---------------------------------------------------------------------------------
# how the rig moves
# ---------------------------------------------------------------------------------


def smooth_levels(t, times, levels, blend):
    """A signal that steps from ``levels[k-1]`` to ``levels[k]`` at ``times[k-1]`` by a
    raised cosine ``blend`` [s] wide (``levels`` has one more entry than ``times``)."""
    out = np.full(t.size, float(levels[0]))
    for when, before, after in zip(times, levels[:-1], levels[1:]):
        share = np.clip((t - when) / blend + 0.5, 0.0, 1.0)
        out += (after - before) * 0.5 * (1.0 - np.cos(math.pi * share))
    return out


def integrate(t, v, x0=0.0):
    """Position of a velocity sampled at ``t`` (trapezoids)."""
    return x0 + np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])


def half_cosine_strokes(rng, t, travel, top_speed, hold=0.0, tiny_share=0.0, tiny=0.0):
    """Strokes between random turning points inside ±travel/2, each a half cosine whose
    peak speed is 0.3–1 of ``top_speed``, with rests of up to ``hold`` [s] at the turning
    points; a ``tiny_share`` of them only ``tiny`` long (inside presliding).

    Returns the position and velocity at ``t`` (exact).
    """
    x, v = np.zeros(t.size), np.zeros(t.size)
    start, position, direction = float(t[0]), 0.0, 1.0
    while start < t[-1]:
        if rng.random() < tiny_share:
            length = tiny * rng.uniform(0.3, 0.9)
        else:
            length = travel * rng.uniform(0.2, 0.6)
        target = position + direction * length
        if abs(target) > travel / 2:
            target = position - direction * length
        delta = target - position
        duration = math.pi * abs(delta) / (2 * top_speed * rng.uniform(0.3, 1.0))
        inside = (t >= start) & (t < start + duration)
        phase = (t[inside] - start) / duration
        x[inside] = position + delta * 0.5 * (1 - np.cos(math.pi * phase))
        v[inside] = delta * math.pi / (2 * duration) * np.sin(math.pi * phase)
        rest = rng.uniform(0.0, hold) if hold else 0.0
        resting = (t >= start + duration) & (t < start + duration + rest)
        x[resting] = target
        start += duration + rest
        position, direction = target, -math.copysign(1.0, delta)
        x[t >= start] = position
    return x, v


def hand_motion(rng, t, travel, top_speed):
    """A joint moved by hand: knots at random places inside ±travel/2 and random
    moments, a quarter of them pauses, most of them turning points (a quarter go on in
    the same direction), joined by a monotone cubic: the speed is irregular,
    continuous, and zero only at the turning points and pauses.

    Returns position, velocity (exact) and the knot times."""
    knots, places, place, direction = [float(t[0])], [0.0], 0.0, 1.0
    while knots[-1] < t[-1]:
        if rng.random() < 0.25:
            step = 0.0  # a pause
            gap = rng.uniform(0.2, 0.8)
        else:
            direction = direction if rng.random() < 0.25 else -direction
            step = direction * travel * rng.uniform(0.15, 0.7)
            if abs(place + step) > travel / 2:
                step, direction = -step, -direction
            gap = max(abs(step) / (top_speed * rng.uniform(0.3, 1.0)), 0.15)
        knots.append(knots[-1] + gap)
        place += step
        places.append(place)
    path = PchipInterpolator(knots, places)
    return path(t), path(t, 1), np.array(knots)


# ---------------------------------------------------------------------------------
# friction along a driven path
# ---------------------------------------------------------------------------------


def _base_levels(rng, Fc_range, drop=(1.1, 1.4)):
    Fc = rng.uniform(*Fc_range)
    return {"Fc": Fc, "Fs": Fc * rng.uniform(*drop), "delta": rng.uniform(0.8, 2.0)}


def driven_friction(x, v, truth, scale=None):
    """(E6') along the driven path x with the steady target d·g·scale + viscous, where
    ``truth`` holds Fc, Fs, V, delta, s and optionally sigma (with n: σ·sgn(v)·|v|ⁿ)
    and ``scale`` multiplies g per sample (a drift, a position dependence)."""
    g = stribeck_magnitude(v, truth["Fc"], truth["Fs"], truth["V"], truth["delta"])
    if scale is not None:
        g = g * scale
    n = truth.get("n", 1.0)
    viscous = truth.get("sigma", 0.0) * np.sign(v) * np.abs(v) ** n
    d = motion_direction(x)
    return presliding_force_from_target(x, d * g + viscous, truth["s"], direction=d)


# ---------------------------------------------------------------------------------
# writing the file and stating the expectation
# ---------------------------------------------------------------------------------


def _timeseries_csv(t, encoder, x_logged, F, force_format, source, rotary):
    columns = {"t [s]": (t, "%.4f"), encoder.header(): (x_logged, POSITION_FORMAT[encoder.unit]),
               f"F [{'N·m' if rotary else 'N'}]": (F, force_format)}
    return csv_text(columns, {"units": "rotary" if rotary else "linear", "source": source})


def in_file_units(truth, per_unit):
    """The truth in a file's units when its positions are logged per ``per_unit`` of
    true travel (degrees: V, s, σ, m_e per degree; levels and α unchanged)."""
    scale = {"V": 1.0 / per_unit, "s": per_unit, "m_e": per_unit,
             "sigma": per_unit ** truth.get("n", 1.0)}
    return {name: value * scale.get(name, 1.0) for name, value in truth.items()}


def _expect(required, truth, F, speed, *, allowed=(), warnings=(), close=(), tol=None,
            required_close=("Fc",), exponent=None, **more) -> Expectation:
    """An expectation with the zoo's defaults: the required effects (and ``allowed``
    ones) only; ``close`` parameters within ``tol`` (default 10 % for levels, 20 % for
    the rest) where determined, ``required_close`` ones determined; a curved viscous
    term's ``exponent`` determined within ±0.15; nothing determined beyond the file's
    forces and speeds; ``input_floor`` present."""
    tol = tol or {}
    within = {}
    for name in close:
        rel = tol.get(name, 0.10 if name in ("Fc", "Fs") else 0.20)
        within[name] = Close(truth[name], rel=rel, required=name in required_close)
    if exponent is not None:
        within["n"] = Close(exponent, abs=0.15, required=True)
    return Expectation(
        required=frozenset(required), allowed=frozenset(required) | frozenset(allowed),
        warnings=tuple(warnings), close=within, input_floor=True,
        force_max=float(np.max(np.abs(F))), speed_max=float(np.max(np.abs(speed))), **more)


def _quantised_x(counts):
    return (("quantised", "x"),) if steps_visible(counts) else ()


# ---------------------------------------------------------------------------------
# the families
# ---------------------------------------------------------------------------------


def coarse_encoder(seed: int = 0, rows: int = 6000, spikes=False) -> Recording:
    """A motor shaft driven back and forth through 60–200 counts or 1–4 revolutions by
    its velocity loop (strokes of half cosines of 0.2–3 s, short rests), logged at 500 Hz
    from an encoder of 10 to 4096 counts per revolution in rad or degrees; a torque
    sensor with 0.5–2 % noise (``spikes``: and 5–30 spikes). Friction: a Stribeck drop of 10–40 % and viscous σ·v rising by 30–80 % of Fc
    at the top speed. Report: viscous, Fc and σ within tolerance, quantised x, the
    noise floor at the sensor's noise (not at what the counts add)."""
    rng = np.random.default_rng(seed)
    encoder = rotary_encoder(rng, 10, 4096)
    travel = max(encoder.count * rng.uniform(60, 200), 2 * math.pi * rng.uniform(1, 4))
    top = travel / rng.uniform(0.6, 1.5)  # a stroke of 0.2–0.6 travel in 0.2–3 s
    t = np.arange(rows) / 500.0
    x, v = half_cosine_strokes(rng, t, travel, top, hold=0.2)
    truth = {**_base_levels(rng, (0.05, 0.3)), "V": top * rng.uniform(0.02, 0.1),
             "s": 1.0 / rng.uniform(2e-4, 2e-3)}
    truth["sigma"] = rng.uniform(0.3, 0.8) * truth["Fc"] / np.max(np.abs(v))
    friction = driven_friction(x, v, truth)
    channel = _sensor(rng, truth["Fc"], **(_spikes(rng, truth["Fc"]) if spikes else {}))
    F = channel.record(t, friction, rng)
    logged, counts = encoder.record(x, rng)
    csv = _timeseries_csv(t, encoder, logged, F, "%.5f",
                          f"motor shaft, velocity loop, {encoder.counts}-count encoder", True)
    file_truth = in_file_units(truth, encoder.per_unit)
    expect = _expect({"viscous"}, file_truth, F, v / encoder.per_unit,
                     warnings=_quantised_x(counts), close=("Fc", "sigma"),
                     required_close=("Fc", "sigma"), noise=channel.floor())
    name = "coarse-encoder-spikes" if spikes else "coarse-encoder"
    return Recording(name, seed, csv, {**file_truth, "counts": encoder.counts,
                                       "unit": encoder.unit, "noise": channel.noise},
                     expect, {"t": t, "x": x, "v": v, "friction": friction, "counts": counts,
                              "encoder": encoder, "channel": channel})


def servo_command(seed: int = 0, rows: int = 6000) -> Recording:
    """A servo axis under a torque command (two tones of 0.5–2 Hz whose amplitude swells
    from 1.2 to 2.5 times Fs), through a 16-bit DAC; the force column is the command.
    An encoder of 256–4096 counts in rad or degrees; inertia and viscous friction both
    matter. Report: inertia and viscous, m_e within tolerance, force-is-command and
    quantised x, the noise floor at the command's own resolution."""
    rng = np.random.default_rng(seed)
    encoder = rotary_encoder(rng, 256, 4096)
    truth = {**_base_levels(rng, (0.02, 0.2)), "s": 1.0 / rng.uniform(2e-3, 1e-2)}
    frequency, top = rng.uniform(0.5, 2.0), rng.uniform(3.0, 15.0)
    truth["V"] = top * rng.uniform(0.02, 0.1)
    truth["sigma"] = rng.uniform(0.3, 0.6) * truth["Fc"] / top
    J = rng.uniform(0.5, 2.0) * truth["Fc"] / (2 * math.pi * frequency * top)
    t = np.arange(rows) / 1000.0
    swell = 1.2 + 1.3 * 0.5 * (1 - np.cos(2 * math.pi * t / t[-1]))
    dac = 20 * truth["Fs"] / 2**16
    command = quantise(truth["Fs"] * swell * two_tone(rng, t, frequency), dac)
    p = friction_params(truth["Fc"], truth["Fs"], truth["V"], truth["delta"], truth["s"], J,
                        sigma=truth["sigma"], damping_ratio=PRESLIDING_DAMPING)
    x, v, friction = run_open_loop(t, command, p, J, substeps=20)
    logged, counts = encoder.record(x, rng)
    csv = _timeseries_csv(t, encoder, logged, command, "%.6f",
                          "servo axis, torque command through a DAC, 1 kHz", True)
    file_truth = in_file_units({**truth, "m_e": J}, encoder.per_unit)
    resolution = max(dac, 1e-6) / math.sqrt(12)
    expect = _expect({"inertia", "viscous"}, file_truth, command, v / encoder.per_unit,
                     warnings=(("force-is-command", "F"), *_quantised_x(counts)),
                     close=("Fc", "sigma", "m_e"), required_close=("m_e",),
                     noise=(resolution, 3.0))
    return Recording("servo-command", seed, csv, {**file_truth, "counts": encoder.counts,
                                                  "unit": encoder.unit, "dac": dac},
                     expect, {"t": t, "x": x, "v": v, "friction": friction, "u": command,
                              "J": J, "counts": counts, "encoder": encoder})


def estimated_torque(seed: int = 0, rows: int = 6000) -> Recording:
    """A robot joint swinging in gravity under a programmed torque (two tones from
    0.1–0.4 Hz, peaks 1.3–2 times Fs). The force column is the analyst's estimate of
    the friction: the programme minus a gravity model computed from the encoder, whose
    mass is 2–6 % off; the amplifier adds an unknown bias of 10–25 % of Fc, and the
    arm's inertia is not removed. An encoder of 1024–16384 counts in rad or degrees, 500 Hz.
    Report: offset (the bias, sign reversed) and viscous, inertia where its share is
    more than 15 % of Fc (allowed otherwise), force-is-command and quantised x, the
    noise floor at what the estimate carries (the gravity model's response to one
    count), not at the residual's size."""
    rng = np.random.default_rng(seed)
    encoder = rotary_encoder(rng, 1024, 16384)
    truth = {**_base_levels(rng, (0.3, 1.5)), "V": rng.uniform(0.02, 0.08),
             "s": 1.0 / rng.uniform(2e-3, 6e-3)}
    Fc, Fs = truth["Fc"], truth["Fs"]
    J = rng.uniform(0.02, 0.1)
    top = rng.uniform(0.3, 1.0)
    truth["sigma"] = rng.uniform(0.3, 0.6) * Fc / top
    mgl = rng.uniform(1.0, 3.0) * Fc
    error = rng.choice([-1.0, 1.0]) * rng.uniform(0.02, 0.06)
    bias = rng.choice([-1.0, 1.0]) * rng.uniform(0.10, 0.25) * Fc
    rate = 500.0
    t = np.arange(rows) / rate
    programme = Fs * rng.uniform(1.3, 2.0) * two_tone(rng, t, rng.uniform(0.1, 0.4))
    p = friction_params(Fc, Fs, truth["V"], truth["delta"], truth["s"], J, sigma=truth["sigma"],
                        damping_ratio=PRESLIDING_DAMPING)
    x, v, friction, counts = _swing(rng, t, p, J, programme, bias, mgl, encoder)
    estimate = np.round(programme - (1 + error) * mgl * np.sin(counts * encoder.count), 4)
    ideal = programme - (1 + error) * mgl * np.sin(x)
    a = np.gradient(v, t)
    logged = counts * encoder.step
    csv = _timeseries_csv(t, encoder, logged, estimate, "%.4f",
                          "joint under a programmed torque; F = programme − gravity model",
                          True)
    file_truth = in_file_units({**truth, "m_e": J, "F_offset": -bias}, encoder.per_unit)
    inertial = float(np.sqrt(np.mean((J * a) ** 2)))
    required = {"offset", "viscous"} | ({"inertia"} if inertial > 0.15 * Fc else set())
    carried = math.hypot(float(np.std(estimate - ideal)), 1e-4 / math.sqrt(12))
    gravity_error = error * mgl * np.sin(x)
    expect = _expect(required, file_truth, estimate, v / encoder.per_unit,
                     allowed={"inertia"},
                     warnings=(("force-is-command", "F"), *_quantised_x(counts)),
                     close=("Fc", "sigma", "F_offset"),
                     tol={"F_offset": 0.2 + float(np.std(gravity_error)) / abs(bias)},
                     noise=(carried, 2.0))
    return Recording("estimated-torque", seed, csv,
                     {**file_truth, "counts": encoder.counts, "unit": encoder.unit,
                      "mgl": mgl, "gravity_error": error, "bias": bias, "inertial": inertial},
                     expect, {"t": t, "x": x, "v": v, "friction": friction,
                              "programme": programme, "counts": counts, "encoder": encoder,
                              "ideal": ideal, "J": J})


def two_tone(rng, t, frequency):
    """A command of unit peak: a sine at ``frequency`` [Hz] and half as much at 2.3–3.1
    times it (an identification experiment's two tones: under one tone alone the
    acceleration would move in step with the position, and an inertia could not be told
    from a spring)."""
    ratio, phase = rng.uniform(2.3, 3.1), rng.uniform(0, 2 * math.pi)
    wave = np.sin(2 * math.pi * frequency * t) + 0.5 * np.sin(2 * math.pi * ratio * frequency * t + phase)
    return wave / np.max(np.abs(wave))


def _swing(rng, t, p, J, programme, bias, mgl, encoder):
    """The joint under ``programme`` + ``bias`` against gravity ``mgl·sin x`` (held
    over each sample), read by ``encoder`` every sample."""
    state = rest_state()
    n = t.size
    dt = float(t[1] - t[0])
    substeps = substeps_for(p, J, dt, 20)
    x, v, friction, counts = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    phase = rng.random() * encoder.count
    for i in range(n):
        x[i], v[i], friction[i] = state[S_X], state[S_V], state[S_F]
        counts[i] = math.floor((state[S_X] + phase) / encoder.count)
        advance(state, p, J, programme[i] + bias - mgl * math.sin(state[S_X]),
                0.0, 0.0, 0.0, dt, substeps)
    return x, v, friction, counts


def hand_moved(seed: int = 0, rows: int = 6000, hum=False, spikes=False) -> Recording:
    """A robot joint moved by hand (irregular speeds up to 0.5–2 rad/s, pauses, turning
    points at random), its 1024–4096-count encoder logged mostly in degrees, a joint
    torque sensor with 0.5–2 % noise and a bias of 10–25 % of Fc, at 100–500 Hz.
    Friction: a Stribeck drop and a viscous rise of 20–40 % of Fc at the top speed.
    Report: offset and viscous within tolerance, quantised x, the noise floor at the
    sensor's noise (with ``hum`` and ``spikes``: mains hum and spikes on the torque)."""
    rng = np.random.default_rng(seed)
    encoder = rotary_encoder(rng, 1024, 4096, degrees=0.7)
    top = rng.uniform(0.5, 2.0)
    truth = {**_base_levels(rng, (0.5, 2.0)), "V": top * rng.uniform(0.01, 0.05),
             "s": 1.0 / rng.uniform(1e-3, 5e-3)}
    offset = rng.choice([-1.0, 1.0]) * rng.uniform(0.10, 0.25) * truth["Fc"]
    rate = float(rng.choice([100.0, 200.0, 500.0]))
    t = np.arange(rows) / rate
    x, v, knots = hand_motion(rng, t, top * rng.uniform(1.0, 2.5), top)
    truth["sigma"] = rng.uniform(0.2, 0.4) * truth["Fc"] / np.max(np.abs(v))
    friction = driven_friction(x, v, truth) + offset
    disturbances = {}
    scale = truth["Fc"]
    if hum:
        disturbances.update(_hum(rng, 0.01 * scale))
    if spikes:
        disturbances.update(_spikes(rng, scale))
    channel = _sensor(rng, scale, **disturbances)
    F = channel.record(t, friction, rng)
    logged, counts = encoder.record(x, rng, np.abs(v) < 1e-3 * top)
    csv = _timeseries_csv(t, encoder, logged, F, "%.5f",
                          "joint moved by hand, joint torque sensor", True)
    file_truth = in_file_units({**truth, "F_offset": offset}, encoder.per_unit)
    expect = _expect({"offset", "viscous"}, file_truth, F, v / encoder.per_unit,
                     warnings=_quantised_x(counts), close=("Fc", "sigma", "F_offset"),
                     required_close=("Fc", "F_offset"), noise=channel.floor())
    name = "hand-moved" + ("-hum" if hum else "") + ("-spikes" if spikes else "")
    return Recording(name, seed, csv, {**file_truth, "counts": encoder.counts,
                                       "unit": encoder.unit, "noise": channel.noise},
                     expect, {"t": t, "x": x, "v": v, "friction": friction, "knots": knots,
                              "counts": counts, "encoder": encoder, "channel": channel})


def constant_acceleration(seed: int = 0, hum=False) -> Recording:
    """A heavy carriage (15–40 kg) on a linear axis accelerated from rest at a constant
    1–3 m/s², then braked at the same rate to a stop, in one direction (up to 1.5 m/s);
    the load cell between drive and carriage reads m·a plus the friction (a Stribeck
    drop, viscous rising by 15–35 % of Fc), 0.2–1 N of noise, at 1 kHz from 0.1–0.3 s
    of rest before the start. Report: inertia (m_e within 10 %) and viscous,
    one-direction, the noise floor at the load cell's (with ``hum``: 50/60 Hz on it)."""
    rng = np.random.default_rng(seed)
    encoder = linear_encoder(rng, belt=True)
    m, a = rng.uniform(15.0, 40.0), rng.uniform(1.0, 3.0)
    half = min(rng.uniform(0.5, 1.5), 1.5 / a)
    truth = {**_base_levels(rng, (10.0, 40.0), (1.1, 1.3)), "V": rng.uniform(0.005, 0.02),
             "s": 1.0 / rng.uniform(2e-5, 1e-4)}
    truth["sigma"] = rng.uniform(0.15, 0.35) * truth["Fc"] / (a * half)
    rest = rng.uniform(0.1, 0.3)
    t = np.arange(0.0, rest + 2 * half, 1e-3)
    moving = np.clip(t - rest, 0.0, 2 * half)
    accelerating = moving < half
    v = np.where(accelerating, a * moving, a * (2 * half - moving))
    x = np.where(accelerating, 0.5 * a * moving**2,
                 a * half**2 - 0.5 * a * (2 * half - moving) ** 2)
    acceleration = np.where(t < rest, 0.0, np.where(accelerating, a, -a))
    friction = driven_friction(x, v, truth)
    noise = rng.uniform(0.2, 1.0)
    channel = ForceChannel(noise, 1000.0 / 2**16, **(_hum(rng, noise) if hum else {}))
    F = channel.record(t, m * acceleration + friction, rng)
    logged, counts = encoder.record(x, rng)
    csv = _timeseries_csv(t, encoder, logged, F, "%.3f",
                          "linear axis, constant acceleration then braking, load cell", False)
    file_truth = {**truth, "m_e": m, "a": a}
    expect = _expect({"inertia", "viscous"}, file_truth, F, v,
                     warnings=(("one-direction", None), *_quantised_x(counts)),
                     close=("Fc", "sigma", "m_e"), tol={"sigma": 0.25},
                     required_close=("Fc", "m_e"), noise=channel.floor())
    return Recording("constant-acceleration" + ("-hum" if hum else ""), seed, csv,
                     {**file_truth, "noise": noise}, expect,
                     {"t": t, "x": x, "v": v, "acceleration": acceleration,
                      "friction": friction, "counts": counts, "encoder": encoder,
                      "channel": channel})


def position_profile(rng, length, size):
    """A smooth, non-periodic dependence on position along a stroke of ``length``: a
    tilt and one or two broad bumps, zero mean over the stroke, peak-to-peak 1 times
    ``size``. Returns a callable of x in [0, length]."""
    xi = np.linspace(0.0, 1.0, 401)
    shape = rng.uniform(-1, 1) * (xi - 0.5)
    for _ in range(rng.integers(1, 3)):
        centre, width = rng.uniform(0.15, 0.85), rng.uniform(0.12, 0.3)
        shape += rng.uniform(0.5, 1.0) * rng.choice([-1, 1]) * np.exp(-((xi - centre) / width) ** 2)
    shape -= shape.mean()
    shape *= size / np.ptp(shape)
    return lambda x: np.interp(np.asarray(x) / length, xi, shape)


def seal_drift(seed: int = 0, pressure=False) -> Recording:
    """A rod drawn end to end through a seal by a linear drive for 60–90 s (strokes of
    40–150 mm at 20–100 mm/s plateaus, short rests at the ends), logged at 100 Hz by a
    load cell with 0.5–1.5 % noise. The seal's friction grows by 15–25 % over the record
    (warming; the same in every stroke and both directions) and varies smoothly with
    the rod's position (the bore's squeeze, not periodic) by more than the drift does.
    Report: drift, α within 25 %, unexplained left (the position dependence the library
    lacks). With ``pressure``: the force is estimated from the chamber pressures of a
    servo-pneumatic cylinder (an offset of the transducers' zero; the rod's small
    inertia is left in): drift and offset."""
    rng = np.random.default_rng(seed)
    encoder = linear_encoder(rng)
    duration, rate = rng.uniform(60.0, 90.0), 100.0
    t = np.arange(0.0, duration, 1.0 / rate)
    length, top = rng.uniform(0.04, 0.15), rng.uniform(0.02, 0.1)
    times, levels, clock, direction = [], [0.0], 0.5, 1.0
    while clock < duration:
        speed = top * rng.uniform(0.4, 1.0)
        times += [clock, clock + length / speed]
        levels += [direction * speed, 0.0]
        clock += length / speed + rng.uniform(0.2, 0.6)
        direction = -direction
    v = smooth_levels(t, times, levels, rng.uniform(0.05, 0.12))
    x = integrate(t, v)
    truth = {**_base_levels(rng, (20.0, 80.0), (1.2, 1.5)), "V": rng.uniform(0.002, 0.008),
             "s": 1.0 / rng.uniform(5e-5, 2e-4)}
    growth = rng.uniform(0.15, 0.25)
    truth["alpha"] = growth / (t[-1] - t[0])
    drift = truth["alpha"] * (t - t[0])
    profile = position_profile(rng, length, 1.0)
    bumps = profile(x)
    # the position dependence is larger than the drift: its spread 1.5–2.5 times
    size = rng.uniform(1.5, 2.5) * float(np.std(drift)) / float(np.std(bumps))
    friction = driven_friction(x, v, truth, scale=(1.0 + drift) * (1.0 + size * bumps))
    required, name, source = {"drift"}, "seal-drift", "rod through a seal, load cell"
    truth_out = dict(truth)
    clean = friction
    if pressure:
        offset = rng.choice([-1.0, 1.0]) * rng.uniform(0.06, 0.15) * truth["Fc"]
        mass = rng.uniform(0.5, 2.0)
        clean = friction + offset + mass * np.gradient(v, t)
        truth_out.update({"F_offset": offset, "m_e": mass})
        required, name = {"drift", "offset"}, "seal-pressure"
        source = "servo-pneumatic cylinder, force from chamber pressures"
    channel = _sensor(rng, truth["Fc"], (0.005, 0.015))
    F = channel.record(t, clean, rng)
    logged, counts = encoder.record(x, rng)
    csv = _timeseries_csv(t, encoder, logged, F, "%.3f", source, False)
    expect = _expect(required, truth_out, F, v, allowed={"inertia"} if pressure else (),
                     warnings=_quantised_x(counts),
                     close=("Fc", "alpha", *(("F_offset",) if pressure else ())),
                     tol={"Fc": 0.15, "alpha": 0.25, "F_offset": 0.3},
                     required_close=("alpha",), noise=channel.floor(), unexplained=True)
    return Recording(name, seed, csv, {**truth_out, "growth": growth, "size": size,
                                       "length": length, "noise": channel.noise}, expect,
                     {"t": t, "x": x, "v": v, "friction": friction, "drift": drift,
                      "bumps": size * bumps, "counts": counts, "encoder": encoder})


def _curved_exponent(rng):
    """An exponent of a curved viscous term well away from 1: 0.3–0.6 or 1.6–2.5."""
    return rng.uniform(0.3, 0.6) if rng.random() < 0.5 else rng.uniform(1.6, 2.5)


def gearbox_steady(seed: int = 0) -> Recording:
    """A gearbox's steady friction curve: 12–30 speed set-points per direction from
    5–50 mrad/s to 1–4 rad/s, each the mean torque of its run (0.3–1 % scatter), the
    friction rising as σ·|v|ⁿ (n 0.3–0.6 or 1.6–2.5) by 50–150 % of Fc; half the seeds
    with a Stribeck drop of 10–30 % that ends inside the sweep. Report: viscous-power,
    n within ±0.15 and Fc within 10 %, both determined."""
    rng = np.random.default_rng(seed)
    n = _curved_exponent(rng)
    v_min, v_max = rng.uniform(0.005, 0.05), rng.uniform(1.0, 4.0)
    Fc = rng.uniform(0.5, 5.0)
    dropped = rng.random() < 0.5
    truth = {"Fc": Fc, "Fs": Fc * (rng.uniform(1.1, 1.3) if dropped else 1.0),
             "V": v_min * rng.uniform(2.0, 10.0), "delta": rng.uniform(0.8, 2.0), "n": n,
             "sigma": rng.uniform(0.5, 1.5) * Fc / v_max**n}
    speeds = np.geomspace(v_min, v_max, rng.integers(12, 31))
    v = np.concatenate([speeds, -speeds])
    clean = np.sign(v) * (stribeck_magnitude(v, Fc, truth["Fs"], truth["V"], truth["delta"])
                          + truth["sigma"] * np.abs(v) ** n)
    scatter = rng.uniform(0.003, 0.01) * Fc
    F = clean + scatter * rng.standard_normal(v.size)
    csv = csv_text({"v [rad/s]": (v, "%.5g"), "F [N·m]": (F, "%.5f")},
                   {"units": "rotary", "source": "gearbox, mean torque per speed set-point"})
    expect = _expect({"viscous-power"}, truth, F, v, close=("Fc", "sigma"), tol={"sigma": 0.3},
                     exponent=n, determined={} if dropped else {"V": False, "delta": False},
                     noise=(scatter, 2.0))
    return Recording("gearbox-steady", seed, csv, {**truth, "scatter": scatter}, expect,
                     {"v": v, "F": F, "clean": clean})


def gearbox_timeseries(seed: int = 0, rows: int = 6000, coarse=False) -> Recording:
    """A gearbox driven by a velocity-controlled motor through speed plateaus of both
    signs (3–100 % of 1–4 rad/s in random order, each held 0.3–1 s and over at least ten
    counts, smooth changes), its output encoder of 1024–4096 counts (``coarse``: 64–512,
    plateaus from 10 %, spikes on the torque) in rad or degrees, a torque sensor with
    0.5–2 % noise. Friction: a Stribeck drop and σ·|v|ⁿ (n 0.3–0.6 or 1.6–2.5) rising by
    50–150 % of Fc. Report: viscous-power, n within ±0.15, Fc within 10 %."""
    rng = np.random.default_rng(seed)
    encoder = rotary_encoder(rng, 64, 512) if coarse else rotary_encoder(rng, 1024, 4096)
    n = _curved_exponent(rng)
    v_max = rng.uniform(1.0, 4.0)
    truth = {**_base_levels(rng, (0.5, 5.0)), "V": v_max * rng.uniform(0.005, 0.02),
             "s": 1.0 / rng.uniform(1e-3, 5e-3), "n": n}
    rise = rng.uniform(0.5, 1.5) * truth["Fc"]
    rate = float(rng.choice([500.0, 1000.0]))
    t = np.arange(rows) / rate
    # each plateau covers at least ten counts (the slowest ones are held longer)
    grid = v_max * np.geomspace(0.1 if coarse else 0.03, 1.0, 12)[rng.permutation(12)]
    times, levels, clock = [], [0.0], 0.2
    while clock < t[-1]:
        speed = grid[len(times) % grid.size]
        times.append(clock)
        levels.append(speed * (-1.0) ** len(times))
        clock += max(rng.uniform(0.3, 1.0), 10 * encoder.count / speed)
    v = smooth_levels(t, times, levels, rng.uniform(0.05, 0.15))
    x = integrate(t, v)
    truth["sigma"] = rise / np.max(np.abs(v)) ** n
    friction = driven_friction(x, v, truth)
    channel = _sensor(rng, truth["Fc"], **(_spikes(rng, truth["Fc"]) if coarse else {}))
    F = channel.record(t, friction, rng)
    logged, counts = encoder.record(x, rng)
    csv = _timeseries_csv(t, encoder, logged, F, "%.5f",
                          "gearbox, velocity-controlled motor, output torque sensor", True)
    file_truth = in_file_units(truth, encoder.per_unit)
    expect = _expect({"viscous-power"}, file_truth, F, v / encoder.per_unit,
                     warnings=_quantised_x(counts), close=("Fc",), exponent=n,
                     noise=channel.floor())
    return Recording("gearbox-coarse-spikes" if coarse else "gearbox-timeseries", seed, csv,
                     {**file_truth, "counts": encoder.counts, "unit": encoder.unit,
                      "noise": channel.noise}, expect,
                     {"t": t, "x": x, "v": v, "friction": friction, "counts": counts,
                      "encoder": encoder, "channel": channel, "times": times,
                      "levels": levels})


def _stroke_rig(rng, rows, rate, levels_range=(5.0, 20.0)):
    """A linear stroke rig: encoder, time, strokes of half cosines over 10–40 mm at up
    to 10–50 mm/s (a fifth of them inside presliding), friction levels."""
    encoder = linear_encoder(rng)
    top, travel = rng.uniform(0.01, 0.05), rng.uniform(0.01, 0.04)
    presliding = rng.uniform(1e-4, 5e-4)
    truth = {**_base_levels(rng, levels_range, (1.2, 1.5)), "V": top * rng.uniform(0.05, 0.2),
             "s": 1.0 / presliding}
    t = np.arange(rows) / rate
    x, v = half_cosine_strokes(rng, t, travel, top, hold=0.2, tiny_share=0.2, tiny=presliding)
    return encoder, truth, t, x, v, top


def strokes_disturbed(seed: int = 0, rows: int = 6000, disturbance: str = "hum") -> Recording:
    """Strokes on a linear rig (half cosines over 10–40 mm, up to 10–50 mm/s, rests and
    presliding strokes), a load cell with 0.5–2 % noise and a ``disturbance``:
    ``"hum"``, 50 or 60 Hz on the force, 2–6 times the noise, sampled at 200, 500 or
    1000 Hz; ``"spikes"``, 5–30 isolated spikes of 20–120 % of Fc. The friction holds a
    viscous rise of 15–35 % of Fc at the fastest speed, or (half the spiked seeds) a load-cell bias of
    5–15 % of Fc instead. Report: that effect within tolerance, nothing else, the noise
    floor at the load cell's (hum: between the noise and the noise with the hum)."""
    rng = np.random.default_rng(seed)
    rate = float(rng.choice([200.0, 500.0, 1000.0])) if disturbance == "hum" else 1000.0
    encoder, truth, t, x, v, top = _stroke_rig(rng, rows, rate)
    effect = "viscous" if disturbance == "hum" or rng.random() < 0.5 else "offset"
    offset = 0.0
    if effect == "viscous":
        truth["sigma"] = rng.uniform(0.15, 0.35) * truth["Fc"] / np.max(np.abs(v))
    else:
        offset = rng.choice([-1.0, 1.0]) * rng.uniform(0.05, 0.15) * truth["Fc"]
        truth["F_offset"] = offset
    friction = driven_friction(x, v, truth) + offset
    noise_share = rng.uniform(0.005, 0.02)
    extra = _hum(rng, noise_share * truth["Fc"]) if disturbance == "hum" \
        else _spikes(rng, truth["Fc"])
    channel = ForceChannel(noise_share * truth["Fc"], 40.0 * truth["Fc"] / 2**16, **extra)
    F = channel.record(t, friction, rng)
    logged, counts = encoder.record(x, rng, np.abs(v) < 1e-3 * top)
    csv = _timeseries_csv(t, encoder, logged, F, "%.4f", f"strokes, load cell ({disturbance})",
                          False)
    expect = _expect({effect}, truth, F, v, warnings=_quantised_x(counts),
                     close=("Fc", "sigma" if effect == "viscous" else "F_offset"),
                     required_close=("Fc", "sigma" if effect == "viscous" else "F_offset"),
                     noise=channel.floor())
    return Recording(f"strokes-{disturbance}", seed, csv,
                     {**truth, "effect": effect, "noise": channel.noise}, expect,
                     {"t": t, "x": x, "v": v, "friction": friction, "counts": counts,
                      "encoder": encoder, "channel": channel})


def short_viscous(seed: int = 0) -> Recording:
    """A short, poorly excited record (1200–2500 rows at 500 Hz or 1 kHz): 3–6 strokes
    at one or two plateau speeds of 5–90 mm/s, a Stribeck drop whose V is 0.2–0.6 of the
    plateau speed (so the drop and a curvature of the viscous term trade) and a linear
    viscous rise of 20–40 % of Fc. Report: viscous, never viscous-power."""
    rng = np.random.default_rng(seed)
    encoder = linear_encoder(rng)
    rate = float(rng.choice([500.0, 1000.0]))
    t = np.arange(int(rng.integers(1200, 2501))) / rate
    speeds = rng.uniform(0.005, 0.03) * np.array([1.0, rng.uniform(1.5, 3.0)])
    speeds = speeds[: rng.integers(1, 3)]
    strokes = int(rng.integers(3, 7))
    rests = rng.uniform(0.05, 0.2, strokes)
    # the slower speed's strokes fill the record; faster ones leave a rest at its end
    length = speeds[0] * (t[-1] - 0.2 - rests.sum()) / strokes
    times, levels, clock = [], [0.0], 0.1
    for k in range(strokes):
        speed = float(rng.choice(speeds))
        times += [clock, clock + length / speed]
        levels += [(-1.0) ** k * speed, 0.0]
        clock += length / speed + rests[k]
    v = smooth_levels(t, times, levels, rng.uniform(0.03, 0.08))
    x = integrate(t, v)
    top = float(np.max(np.abs(v)))
    truth = {**_base_levels(rng, (5.0, 20.0), (1.2, 1.5)), "V": top * rng.uniform(0.2, 0.6),
             "s": 1.0 / rng.uniform(1e-4, 5e-4)}
    truth["sigma"] = rng.uniform(0.2, 0.4) * truth["Fc"] / top
    friction = driven_friction(x, v, truth)
    channel = _sensor(rng, truth["Fc"])
    F = channel.record(t, friction, rng)
    logged, counts = encoder.record(x, rng)
    csv = _timeseries_csv(t, encoder, logged, F, "%.4f", "short strokes, load cell", False)
    # the drop and the viscous rise trade: only gross errors in what is called determined
    expect = _expect({"viscous"}, truth, F, v, warnings=_quantised_x(counts),
                     close=("Fc", "sigma"), tol={"Fc": 0.25, "sigma": 0.5}, required_close=(),
                     noise=channel.floor())
    return Recording("short-viscous", seed, csv, {**truth, "speeds": speeds,
                                                  "noise": channel.noise}, expect,
                     {"t": t, "x": x, "v": v, "friction": friction, "levels": levels,
                      "counts": counts, "encoder": encoder})


def _steady_speeds(rng, v_min, v_max, per_direction):
    speeds = np.geomspace(v_min, v_max, per_direction)
    return np.concatenate([speeds, -speeds * rng.uniform(0.97, 1.03, speeds.size)])


def offset_steady(seed: int = 0) -> Recording:
    """A steady friction curve, both directions (10–25 set-points each, 1 mm/s to
    0.1–0.5 m/s), from a load cell with a bias of 5–15 % of Fc: the same Stribeck curve
    in both directions plus a linear viscous rise of 20–60 % of Fc, shifted by the bias.
    Report: offset and viscous; never asymmetry (it fits as well with more parameters,
    MODEL.md §7's parsimony), never viscous-power (the viscous term is straight)."""
    rng = np.random.default_rng(seed)
    v_max = rng.uniform(0.1, 0.5)
    v = _steady_speeds(rng, rng.uniform(5e-4, 2e-3), v_max, rng.integers(10, 26))
    Fc = rng.uniform(5.0, 50.0)
    truth = {"Fc": Fc, "Fs": Fc * rng.uniform(1.1, 1.4), "V": rng.uniform(0.003, 0.02),
             "delta": rng.uniform(0.8, 2.0), "sigma": rng.uniform(0.2, 0.6) * Fc / v_max,
             "F_offset": rng.choice([-1.0, 1.0]) * rng.uniform(0.05, 0.15) * Fc}
    clean = np.sign(v) * stribeck_magnitude(v, Fc, truth["Fs"], truth["V"], truth["delta"]) \
        + truth["sigma"] * v + truth["F_offset"]
    scatter = rng.uniform(0.003, 0.01) * Fc
    F = clean + scatter * rng.standard_normal(v.size)
    csv = csv_text({"v [m/s]": (v, "%.5g"), "F [N]": (F, "%.4f")},
                   {"source": "friction curve, mean force per speed set-point"})
    expect = _expect({"offset", "viscous"}, truth, F, v, close=("Fc", "sigma", "F_offset"),
                     required_close=("Fc", "F_offset"), noise=(scatter, 2.0))
    return Recording("offset-steady", seed, csv, {**truth, "scatter": scatter}, expect,
                     {"v": v, "F": F, "clean": clean})


def unresolved_drop(rng, Fc, v_max, far):
    """No Stribeck drop at all (Fs = Fc), or (``far``) a drop of 5–20 % of Fc whose V is
    20–100 times the fastest speed (the data hold its first 1 % at most)."""
    if not far:
        return {"Fc": Fc, "Fs": Fc, "V": v_max, "delta": 1.0}
    return {"Fc": Fc, "Fs": Fc * rng.uniform(1.05, 1.2), "V": v_max * rng.uniform(20, 100),
            "delta": rng.uniform(0.8, 2.0)}


def flat_steady(seed: int = 0) -> Recording:
    """A steady curve whose Stribeck drop the data do not resolve (:func:`unresolved_drop`,
    the far drop on odd seeds; 1–10 mm/s up to 5–30 times that; the sliding level 3–10 N
    with 0.3–1 % scatter), half the seeds with a linear viscous rise of 15–40 % of Fc. Report: Fc determined
    within 5 % of the sliding level the data show; V and δ not determined, and a V above
    the fastest speed called beyond-data; viscous exactly where it is in the data."""
    rng = np.random.default_rng(seed)
    v_min = rng.uniform(1e-3, 1e-2)
    v_max = v_min * rng.uniform(5.0, 30.0)
    v = _steady_speeds(rng, v_min, v_max, rng.integers(10, 26))
    truth = unresolved_drop(rng, rng.uniform(3.0, 10.0), v_max, far=seed % 2 == 1)
    sigma = rng.uniform(0.15, 0.4) * truth["Fc"] / v_max if rng.random() < 0.5 else 0.0
    g = stribeck_magnitude(v, truth["Fc"], truth["Fs"], truth["V"], truth["delta"])
    clean = np.sign(v) * g + sigma * v
    scatter = rng.uniform(0.003, 0.01) * truth["Fc"]
    F = clean + scatter * rng.standard_normal(v.size)
    csv = csv_text({"v [m/s]": (v, "%.5g"), "F [N]": (F, "%.4f")},
                   {"source": "friction curve of a dry slide"})
    truth.update(sigma=sigma, level=float(np.mean(g)))
    expect = _expect({"viscous"} if sigma else set(), {**truth, "Fc": truth["level"]}, F, v,
                     close=("Fc", *(("sigma",) if sigma else ())), tol={"Fc": 0.05},
                     determined={"V": False, "delta": False}, beyond_speed=True,
                     noise=(scatter, 2.0), unexplained=False)
    return Recording("flat-steady", seed, csv, {**truth, "scatter": scatter}, expect,
                     {"v": v, "F": F, "clean": clean})


def flat_timeseries(seed: int = 0, rows: int = 5000) -> Recording:
    """Strokes on a linear rig (as :func:`strokes_disturbed`, up to 10–50 mm/s) whose
    Stribeck drop the data do not resolve (:func:`unresolved_drop`, the far drop on odd
    seeds; a sliding level of
    3–10 N from the first micrometres of sliding on), read by a load cell with 0.5–2 %
    noise. Report: no effect; Fc determined within 5 % of the sliding level; V and δ
    not determined, a V above the fastest speed called beyond-data."""
    rng = np.random.default_rng(seed)
    encoder, rig, t, x, v, top = _stroke_rig(rng, rows, 1000.0, (3.0, 10.0))
    truth = {**unresolved_drop(rng, rig["Fc"], float(np.max(np.abs(v))), far=seed % 2 == 1),
             "s": rig["s"]}
    friction = driven_friction(x, v, truth)
    channel = _sensor(rng, truth["Fc"])
    F = channel.record(t, friction, rng)
    logged, counts = encoder.record(x, rng, np.abs(v) < 1e-3 * top)
    csv = _timeseries_csv(t, encoder, logged, F, "%.4f", "strokes of a dry slide, load cell",
                          False)
    sliding = np.abs(v) > 0
    truth["level"] = float(np.mean(stribeck_magnitude(v[sliding], truth["Fc"], truth["Fs"],
                                                      truth["V"], truth["delta"])))
    expect = _expect(set(), {**truth, "Fc": truth["level"]}, F, v,
                     warnings=_quantised_x(counts), close=("Fc",), tol={"Fc": 0.05},
                     determined={"V": False, "delta": False}, beyond_speed=True,
                     noise=channel.floor(), unexplained=False)
    return Recording("flat-timeseries", seed, csv, {**truth, "noise": channel.noise}, expect,
                     {"t": t, "x": x, "v": v, "friction": friction, "counts": counts})


def families() -> dict:
    """Every family of the zoo by name: a callable of the seed."""
    from functools import partial

    return {
        "coarse-encoder": coarse_encoder,
        "servo-command": servo_command,
        "estimated-torque": estimated_torque,
        "hand-moved": hand_moved,
        "constant-acceleration": constant_acceleration,
        "seal-drift": seal_drift,
        "gearbox-steady": gearbox_steady,
        "gearbox-timeseries": gearbox_timeseries,
        "strokes-hum": partial(strokes_disturbed, disturbance="hum"),
        "strokes-spikes": partial(strokes_disturbed, disturbance="spikes"),
        "short-viscous": short_viscous,
        "offset-steady": offset_steady,
        "flat-steady": flat_steady,
        "flat-timeseries": flat_timeseries,
        # combinations
        "hand-moved-hum-spikes": partial(hand_moved, hum=True, spikes=True),
        "seal-pressure": partial(seal_drift, pressure=True),
        "gearbox-coarse-spikes": partial(gearbox_timeseries, coarse=True),
        "constant-acceleration-hum": partial(constant_acceleration, hum=True),
        "coarse-encoder-spikes": partial(coarse_encoder, spikes=True),
    }
