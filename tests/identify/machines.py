"""Seeded recordings that look like real machines (issue 19), each with what its report
must say.

Every family is physics first: the plant is integrated with its friction
(:mod:`tests.identify.plant`), or the friction is run along a driven position with
the core's (E6') (:func:`breakaway.presliding.presliding_force_from_target`), and only
then does the recording happen: an encoder's counts, a DAC's steps in a commanded force,
a load cell's noise and an ADC's steps where a sensor exists, and the decimals the
logger prints. The seed draws every parameter within a physically plausible range, so
that the engine is scored on a family, not on one file.

Each generator returns a :class:`Recording`: the CSV text a user would upload, the
truth, the :class:`~tests.identify.expectations.Expectation` of its report, and the
hidden true signals (for the generators' own tests). The families of issue 19 are
here; the machine-like versions of issue 9's classes are in
:mod:`tests.identify.machines_classic`. :func:`families` lists all of them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial

import numpy as np

from .expectations import Close, Expectation
from .plant import (SHAPE_EXPONENTIAL, advance, csv_text, encoder_counts,
                    friction_params, quantise, rest_state, run_open_loop, substeps_for, S_V, S_X)

#: A servo's torque command: its amplitude [N·m] and DAC step [N·m] (issue 19).
SERVO_AMPLITUDE, SERVO_DAC_STEP = 0.05, 5e-5
#: Counts per revolution of the servo's encoder and of the degree-logging joint's.
SERVO_COUNTS, DEGREE_COUNTS = 10_000, 4096
#: An encoder record is at rest below this share of its top speed (where it flickers).
REST_SHARE = 1e-3


@dataclass
class Recording:
    """One machine-like file: the CSV a user uploads and what is true about it."""

    family: str
    seed: int
    csv: str
    truth: dict
    expect: Expectation
    hidden: dict = field(default_factory=dict, repr=False)


def triangle(phase):
    """A unit triangle wave of period 1: 0 at phase 0, +1 at 1/4, −1 at 3/4."""
    return 2.0 * np.abs(2.0 * ((np.asarray(phase) + 0.75) % 1.0) - 1.0) - 1.0


# ---------------------------------------------------------------------------------
# a. servo axis under a torque command
# ---------------------------------------------------------------------------------


def servo_axis(seed: int = 0, rows: int = 10_000) -> Recording:
    """A servo axis driven back and forth by a triangle torque command of ±0.05 N·m.

    1 kHz; the force column is the command as the DAC takes it (steps of 5e-5 N·m), the
    position a 10,000-count encoder in rad. Inertia dominates (J of 1.5–3e-4 kg·m²); the
    negative direction slides 20–30 % harder or softer (levels scaled, the Stribeck gap
    with them); presliding is Dahl-like, f(z) = 1 − exp(−3z), outside the library; the
    current loop adds an unrecorded torque ripple of 1e-4 N·m.
    """
    rng = np.random.default_rng(seed)
    t = np.arange(rows) / 1000.0
    J = rng.uniform(1.5e-4, 3e-4)
    Fc = rng.uniform(0.012, 0.022)
    Fs = Fc * rng.uniform(1.2, 1.5)
    ratio = 1.0 + rng.choice([-1.0, 1.0]) * rng.uniform(0.2, 0.3)
    V, delta = 10 ** rng.uniform(-1.3, -0.3), rng.uniform(0.8, 2.0)
    reach = rng.uniform(5e-3, 1.5e-2)  # presliding distance [rad]
    command = SERVO_AMPLITUDE * triangle(t / rng.uniform(1.5, 3.0) + rng.random())
    F = quantise(command, SERVO_DAC_STEP)
    ripple = 1e-4 * rng.standard_normal(rows)
    p = friction_params(Fc, Fs, V, delta, 1.0 / reach, J, SHAPE_EXPONENTIAL,
                        Fc_neg=ratio * Fc, Fs_neg=ratio * Fs)
    x, v, friction = run_open_loop(t, F + ripple, p, J, substeps=100)
    count = 2 * math.pi / SERVO_COUNTS
    recorded = encoder_counts(x, count, rng) * count
    csv = csv_text({"t": (t, "%.3f"), "x": (recorded, "%.6f"), "F": (F, "%.5f")},
                   {"units": "rotary", "source": "servo axis, torque command, 1 kHz"})
    truth = {"m_e": J, "Fc": Fc, "Fs": Fs, "Fc_neg": ratio * Fc, "Fs_neg": ratio * Fs,
             "V": V, "delta": delta, "reach": reach, "count": count}
    levels = {k: Close(truth[k]) for k in ("Fc", "Fs", "Fc_neg", "Fs_neg")}
    expect = Expectation(
        required=frozenset({"inertia", "asymmetry"}), allowed=frozenset({"inertia", "asymmetry"}),
        any_warnings=((("quantised", "x"), ("quantised", "F"), ("force-is-command", "F")),),
        close={"m_e": Close(J, required=True), **levels}, unexplained=True,
        structure=("x - x_r", "time since reversal"),
        force_max=float(np.max(np.abs(F))), speed_max=float(np.max(np.abs(v))))
    return Recording("servo-axis", seed, csv, truth, expect,
                     {"t": t, "x": x, "v": v, "friction": friction, "u": F + ripple, "J": J})


# ---------------------------------------------------------------------------------
# b. steady friction curves of robot joints
# ---------------------------------------------------------------------------------


def joint_steady(seed: int = 0, exponent: float = 0.4) -> Recording:
    """A robot joint's friction at constant speeds, both directions, 24–36 set-points per
    direction from near standstill (5–20 mrad/s) to about 2.5 rad/s.

    Friction rises as ``Fc + σ·|v|ⁿ`` by 60–120 % of Fc at the fastest set-point. No
    Stribeck drop (Fs = Fc): a lubricated harmonic drive's drop ends below the slowest
    set-point of such a sweep. Each point is the mean torque over 2–4 s at 1 kHz: the
    sensor's noise (2–5 % of Fc) averages down, the gear's torque ripple (2 per wave
    generator turn, 2–5 % of Fc) does not where the window holds less than a period.
    """
    rng = np.random.default_rng(seed)
    Fc = rng.uniform(1.0, 4.0)
    v_min, v_max = rng.uniform(0.005, 0.02), rng.uniform(2.2, 2.8)
    sigma = rng.uniform(0.6, 1.2) * Fc / v_max**exponent
    speeds = np.geomspace(v_min, v_max, rng.integers(24, 37))
    v = np.concatenate([speeds, -speeds])
    window = rng.uniform(2.0, 4.0, v.size)
    wavelength = 2 * math.pi / (2 * rng.choice([50, 80, 100, 120, 160]))  # [rad]
    start = rng.uniform(0, 2 * math.pi, v.size)
    end = start + 2 * math.pi * np.abs(v) * window / wavelength
    ripple = rng.uniform(0.02, 0.05) * Fc * (np.cos(start) - np.cos(end)) / (end - start)
    noise = rng.uniform(0.02, 0.05) * Fc / np.sqrt(1000 * window) * rng.standard_normal(v.size)
    clean = np.sign(v) * (Fc + sigma * np.abs(v) ** exponent)
    F = clean + ripple + noise
    csv = csv_text({"v [rad/s]": (v, "%.4g"), "F [N·m]": (F, "%.4f")},
                   comments=("joint friction sweep: mean torque per speed set-point",))
    truth = {"Fc": Fc, "sigma": sigma, "n": exponent}
    expect = Expectation(
        required=frozenset({"viscous-power"}), allowed=frozenset({"viscous-power"}),
        determined={"Fc": True, "V": False, "delta": False},
        close={"Fc": Close(Fc, required=True), "n": Close(exponent, abs=0.1, required=True)},
        force_max=float(np.max(np.abs(F))), speed_max=v_max)
    return Recording(f"joint-steady-n{exponent:g}", seed, csv, truth, expect,
                     {"v": v, "F": F, "clean": clean})


# ---------------------------------------------------------------------------------
# c. presliding records that never reach gross sliding
# ---------------------------------------------------------------------------------

_Z = np.concatenate([[0.0], np.geomspace(1e-12, 1.0, 4000)])
_F_OF_Z = np.where(_Z > 0, _Z * (1 - np.log(np.where(_Z > 0, _Z, 1.0))), 0.0)


def quasistatic_presliding(u, Fs, s):
    """Positions under a slow force ``u`` that stays inside presliding, by (E6') with
    the target at standstill, d·g(0) = d·Fs, inverted for x: each turning point of u
    starts a branch (x_r, F_r), and f(s·|x − x_r|) = (u − F_r)/(d·Fs − F_r)."""
    x = np.zeros(u.size)
    x_r, F_r, d = 0.0, 0.0, 1.0
    for i in range(1, u.size):
        step = u[i] - u[i - 1]
        if step * d < 0:  # the force turns: a reversal at the previous sample
            x_r, F_r, d = x[i - 1], u[i - 1], -d
        share = (u[i] - F_r) / (d * Fs - F_r)
        x[i] = x_r + d * np.interp(share, _F_OF_Z, _Z) / s
    return x


def _presliding_record(family, seed, rng, t, u, Fs, truth):
    """Encoder, torque sensor and expectation shared by the presliding families."""
    x = quasistatic_presliding(u, Fs, truth["s"])
    count = 2 * math.pi / 2 ** rng.choice([20, 21, 22])
    u_max = float(np.max(u))
    noise = rng.uniform(0.002, 0.005) * u_max
    measured = quantise(u + noise * rng.standard_normal(u.size), 4 * u_max / 2**16)
    recorded = encoder_counts(x, count, rng) * count
    csv = csv_text({"t": (t, "%.3f"), "x": (recorded, "%.9f"), "F": (measured, "%.4f")},
                   {"units": "rotary", "source": "joint on a test bench, open-loop torque"})
    held = float(np.max(measured))
    v = np.gradient(x, t)
    expect = Expectation(
        warnings=(("beyond-data", "Fs"),),
        determined={"Fs": False, "Fc": False, "V": False, "delta": False},
        lower_bound=("Fs", held), force_max=held, speed_max=float(np.max(np.abs(v))))
    return Recording(family, seed, csv, {**truth, "held": held, "noise": noise}, expect,
                     {"t": t, "x": x, "u": u, "count": count, "Fs": Fs})


def _joint_far_from_sliding(rng):
    u_max = rng.uniform(8.0, 20.0)
    Fs = u_max * rng.uniform(3.0, 8.0)
    truth = {"Fs": Fs, "Fc": Fs * rng.uniform(0.6, 0.85), "s": 1.0 / rng.uniform(5e-3, 2e-2)}
    return u_max, truth


def presliding_ramps(seed: int = 0) -> Recording:
    """Slow open-loop torque ramps up and back to zero (4–6 of them, peaks up to 8–20
    N·m, 2–8 s up), one direction, on a joint whose Fs is 3–8 times the largest torque:
    the record never leaves presliding. 200 Hz, a 20–22 bit encoder, a torque sensor."""
    rng = np.random.default_rng(seed)
    u_max, truth = _joint_far_from_sliding(rng)
    peaks = u_max * rng.uniform(0.4, 1.0, rng.integers(4, 7))
    peaks[rng.integers(peaks.size)] = u_max
    times, values = [0.0], [0.0]
    for peak in peaks:
        times += [times[-1] + rng.uniform(0.5, 2.0), 0.0, 0.0]
        times[-2] = times[-3] + rng.uniform(2.0, 8.0)
        times[-1] = times[-2] + rng.uniform(1.0, 4.0)
        values += [0.0, peak, 0.0]
    t = np.arange(0.0, times[-1] + 1.0, 0.005)
    return _presliding_record("presliding-ramps", seed, rng, t, np.interp(t, times, values),
                              truth["Fs"], truth)


def presliding_sine(seed: int = 0) -> Recording:
    """A torque loaded to a mean level and then varied as a sine in three growing
    amplitudes (minor loops inside presliding), one direction, Fs 3–8 times the
    largest torque. 200 Hz, 30 s."""
    rng = np.random.default_rng(seed)
    u_max, truth = _joint_far_from_sliding(rng)
    mean = u_max * rng.uniform(0.5, 0.7)
    amplitude = (u_max - mean) * np.repeat([0.4, 0.7, 1.0], 2000)
    t = np.arange(6000) * 0.005 + 2.0
    u = mean + amplitude * np.sin(2 * math.pi * rng.uniform(0.2, 0.6) * (t - 2.0))
    load = np.arange(400) * 0.005
    return _presliding_record("presliding-sine", seed, rng, np.concatenate([load, t]),
                              np.concatenate([mean * load / 2.0, u]), truth["Fs"], truth)


# ---------------------------------------------------------------------------------
# d. creep with stick-slip
# ---------------------------------------------------------------------------------


def stick_slip_creep(seed: int = 0, rows: int = 10_000) -> Recording:
    """A stage dragged through a spring at a slow, slightly uneven speed (0.5–2 mm/s,
    ±3 %): friction weakening with speed makes it stick and slip. The force column is
    the load cell in the spring (friction plus m·a), the position a linear encoder.
    1 kHz; no position-locked friction at all."""
    rng = np.random.default_rng(seed)
    m, stiffness = rng.uniform(0.5, 2.0), rng.uniform(3e3, 1e4)
    speed = rng.uniform(0.5e-3, 2e-3)
    Fc = rng.uniform(5.0, 15.0)
    Fs = Fc * rng.uniform(1.3, 1.6)
    V, delta = rng.uniform(2e-4, 1e-3), rng.uniform(0.8, 1.5)
    s = 1.0 / rng.uniform(20e-6, 80e-6)
    t = np.arange(rows) / 1000.0
    uneven = np.cumsum(rng.standard_normal(rows))
    uneven = np.convolve(uneven - uneven.mean(), np.ones(500) / 500, mode="same")
    uneven *= 0.03 / max(float(np.max(np.abs(uneven))), 1e-12)
    drive = np.cumsum(speed * (1.0 + uneven)) / 1000.0
    p = friction_params(Fc, Fs, V, delta, s, m)
    x, v, friction = run_open_loop(t, np.zeros(rows), p, m, substeps=100, drive=drive,
                                   stiffness=stiffness)
    spring = stiffness * (drive - x)
    noise = rng.uniform(0.01, 0.03)
    measured = quantise(spring + noise * rng.standard_normal(rows), 100.0 / 2**16)
    count = rng.choice([5e-8, 1e-7, 5e-7])
    recorded = encoder_counts(x, count, rng) * count
    csv = csv_text({"t": (t, "%.3f"), "x": (recorded, "%.8f"), "F": (measured, "%.4f")},
                   {"source": "stage dragged through a spring, load cell in the spring"})
    truth = {"Fc": Fc, "Fs": Fs, "V": V, "delta": delta, "s": s, "m_e": m, "speed": speed,
             "stiffness": stiffness, "noise": noise}
    expect = Expectation(
        allowed=frozenset({"inertia"}), warnings=(("stick-slip", None), ("one-direction", None)),
        close={"Fc": Close(Fc), "Fs": Close(Fs)},
        force_max=float(np.max(np.abs(measured))), speed_max=float(np.max(np.abs(v))))
    return Recording("stick-slip-creep", seed, csv, truth, expect,
                     {"t": t, "x": x, "v": v, "spring": spring, "friction": friction})


# ---------------------------------------------------------------------------------
# e. encoder counts written in degrees, a commanded torque
# ---------------------------------------------------------------------------------


def joint_in_degrees(seed: int = 0, command: str = "ramp", rows: int = 8000) -> Recording:
    """A joint moved by a commanded torque, its 4096-count encoder logged in degrees
    with 4 decimals (steps of 0.0879 or 0.0878: q and the printed rounding).

    ``command``: ``"ramp"``, a programmed torque cycle (ramp to +1.3–1.8 Fs and back,
    rest at zero, the same negative, rest) computed every millisecond; ``"steps"``,
    the same held at a PLC's 20–100 Hz update; or ``"controller"``, the output of a
    PID position loop on the encoder reading that follows a sine. The encoder
    flickers by one count at rest; the force column has no noise (the noise is in x).
    Symmetric friction with E4 presliding (and the plant's presliding damping).
    """
    rng = np.random.default_rng(seed)
    J = rng.uniform(1e-3, 4e-3)
    Fc = rng.uniform(0.15, 0.4)
    Fs = Fc * rng.uniform(1.1, 1.4)
    V, delta = rng.uniform(0.02, 0.1), rng.uniform(1.0, 2.0)
    s = 1.0 / rng.uniform(3e-3, 9e-3)
    p = friction_params(Fc, Fs, V, delta, s, J)
    t = np.arange(rows) / 1000.0
    count = 2 * math.pi / DEGREE_COUNTS
    if command == "controller":
        x, v, F, counts = _position_loop(rng, t, p, J, Fs, count)
    else:
        update = rng.uniform(20.0, 100.0)  # the PLC's rate [Hz]
        clock = t if command == "ramp" else np.floor(t * update) / update
        F = np.round(Fs * rng.uniform(1.3, 1.8) * programmed_cycle(
            clock, rng.uniform(0.4, 1.0), rng.uniform(0.3, 0.8)), 4)
        x, v, _ = run_open_loop(t, F, p, J, substeps=40)
        counts = encoder_counts(x, count, rng, np.abs(v) < REST_SHARE * np.max(np.abs(v)))
    degrees = counts * (360.0 / DEGREE_COUNTS)
    csv = csv_text({"t [s]": (t, "%.3f"), "x [deg]": (degrees, "%.4f"),
                    "F [N·m]": (F, "%.4f")}, {"source": f"joint, torque {command}, encoder 4096"})
    per_degree = math.pi / 180.0  # the file's x is in degrees: so are V, s and m_e
    truth = {"Fc": Fc, "Fs": Fs, "m_e": J * per_degree, "V": V / per_degree,
             "delta": delta, "s": s * per_degree, "J": J}
    expect = Expectation(
        allowed=frozenset({"inertia"}),
        warnings=(("quantised", "x"), ("force-is-command", "F")),
        close={"Fc": Close(Fc), "Fs": Close(Fs)},
        force_max=float(np.max(np.abs(F))), speed_max=float(np.max(np.abs(v))) / per_degree)
    return Recording(f"degrees-{command}", seed, csv, truth, expect,
                     {"t": t, "x": x, "v": v, "counts": counts, "u": F})


def programmed_cycle(t, ramp, rest):
    """A programmed force cycle of unit peak: up in ``ramp`` [s], down in ``ramp``,
    rest at zero for ``rest`` [s], then the same negative."""
    knots = np.cumsum([0.0, ramp, ramp, rest, ramp, ramp, rest])
    return np.interp(np.asarray(t) % knots[-1], knots, [0, 1, 0, 0, -1, 0, 0])


def _position_loop(rng, t, p, J, Fs, count):
    """A PID position loop at 1 kHz on the encoder reading (derivative on a 5 ms
    filtered velocity), following a sine of 0.5–1.5 rad at 0.2–0.5 Hz; its output
    through a 16-bit DAC of ±3.2768 N·m (steps of 1e-4 N·m)."""
    bandwidth = 2 * math.pi * rng.uniform(3.0, 8.0)
    kp, kd = J * bandwidth**2, 1.4 * J * bandwidth
    ki = kp * bandwidth / 5
    amplitude, frequency = rng.uniform(0.5, 1.5), rng.uniform(0.2, 0.5)
    reference = amplitude * np.sin(2 * math.pi * frequency * t)
    phase = rng.random() * count
    state, integral, v_f = rest_state(), 0.0, 0.0
    n = t.size
    x, v, F, counts = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    dt = float(t[1] - t[0])
    substeps = substeps_for(p, J, dt, 40)
    for i in range(n):
        scaled = (state[S_X] + phase) / count
        reading = math.floor(scaled)
        if abs(state[S_V]) < REST_SHARE * amplitude * 2 * math.pi * frequency \
                and rng.random() < 0.3:
            reading += 1 if scaled - reading >= 0.5 else -1  # flicker across the nearer edge
        counts[i] = reading
        if i:
            v_f += (1 - math.exp(-dt / 5e-3)) * ((counts[i] - counts[i - 1]) * count / dt - v_f)
        error = reference[i] - reading * count
        integral += error * dt
        u = kp * error + ki * integral + kd * (2 * math.pi * frequency * amplitude
                                              * math.cos(2 * math.pi * frequency * t[i]) - v_f)
        F[i] = np.clip(np.round(u, 4), -3.2768, 3.2767)
        x[i], v[i] = state[S_X], state[S_V]
        advance(state, p, J, F[i], 0.0, 0.0, 0.0, dt, substeps)
    return x, v, F, counts


def families() -> dict:
    """Every machine-like family by name: a callable of the seed."""
    from . import machines_classic  # here: it imports this module's Recording

    return {
        "servo-axis": servo_axis,
        "joint-steady-n0.4": partial(joint_steady, exponent=0.4),
        "joint-steady-n2": partial(joint_steady, exponent=2.0),
        "presliding-ramps": presliding_ramps,
        "presliding-sine": presliding_sine,
        "stick-slip-creep": stick_slip_creep,
        "degrees-ramp": partial(joint_in_degrees, command="ramp"),
        "degrees-steps": partial(joint_in_degrees, command="steps"),
        "degrees-controller": partial(joint_in_degrees, command="controller"),
        **machines_classic.FAMILIES,
    }

