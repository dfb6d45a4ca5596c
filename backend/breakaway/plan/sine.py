"""A position sine as a family: ``x = A·sin(2π·f·t)`` from the virgin state, through
presliding and reversals, the friction F recorded at every sample (E6').

After the first quarter period every half period is the same branch (mirrored): it
starts at a reversal with the force of the last one and runs through presliding into
gross sliding when ``A`` exceeds the presliding distance ``1/s``. The information of a
record is therefore that of the first quarter, the first half period and the second
half period counted once for each further half period; each is integrated over time
(samples per second × the time a sample stands for) on a grid that is fine where
(E6') is steep, right after a reversal. The measurement depends on every parameter:
on ``s`` through the presliding branches, on the curve (E2) through gross sliding.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .curve import PARAMETERS
from .family import Candidates, Information
from .programme import empty_csv, sine_csv

#: Points of each branch's presliding arc (geometric in the distance from the reversal)
#: and over the whole branch (uniform in phase).
ARC_POINTS = 48
REST_POINTS = 96
#: The arc runs out to this many presliding distances from the reversal ...
ARC_REACH = 1.5
#: ... from this share of the shortest presliding distance of the draws.
ARC_START = 1e-3
#: A sine is sampled at least this many times per period.
MIN_SAMPLES_PER_PERIOD = 20
#: The record holds at least this many periods.
MIN_PERIODS = 2.0
#: The smallest amplitude tried, in shortest presliding distances (a loop entirely in
#: presliding), and the largest without a travel limit, in longest ones.
SMALLEST_AMPLITUDE = 0.2
LARGEST_AMPLITUDE = 200.0


@njit(cache=True)
def _sine_information(theta, columns, x, v, log_speed, d, weight, info, peak):
    """Fisher information of each (draw, candidate) record, with forward sensitivities
    of (E6') through the reversal memory.

    ``theta``: (Q, 7) Fc, Fs, V, delta, s, sigma, n; ``columns``: the coordinates the
    information is wanted for, indices into Fc, Fs, ln V, delta, ln s, sigma, n;
    ``x, v, log_speed, d, weight``: (G, N) the samples of each candidate's branches in
    order (quarter, half, half), ln|v| (−inf at rest), and the recorded samples each
    stands for divided by σ²;
    ``info``: (Q, G, p, p) out; ``peak``: (Q, G) out, max |F|.
    """
    Q, G, N = theta.shape[0], x.shape[0], x.shape[1]
    p = columns.size
    for job in range(Q * G):
        q, g = job // G, job % G
        Fc, Fs, V, delta, s, sigma, n = theta[q]
        drop = Fs - Fc
        log_V = math.log(V)
        grad = np.zeros(7)
        grad_r = np.zeros(7)
        last = np.zeros(7)
        acc = np.zeros((p, p))
        x_r, F_r, F_last = 0.0, 0.0, 0.0
        top = 0.0
        for i in range(N):
            w = weight[g, i]
            if i > 0 and d[g, i] != d[g, i - 1]:
                x_r, F_r = x[g, i - 1], F_last
                grad_r[:] = last
            speed = abs(v[g, i])
            sign_v = 1.0 if v[g, i] > 0 else (-1.0 if v[g, i] < 0 else 0.0)
            direction = d[g, i]
            if speed > 0:
                ratio = log_speed[g, i] - log_V
                y = math.exp(delta * ratio)
                decay = math.exp(-y)
                power = speed if n == 1.0 else math.exp(n * log_speed[g, i])
                grad[2] = direction * drop * delta * y * decay
                grad[3] = -direction * drop * y * decay * ratio
                grad[5] = sign_v * power
                grad[6] = sign_v * sigma * power * log_speed[g, i]
            else:
                decay = 1.0 if delta > 0 else 0.0
                power = 0.0
                grad[2] = grad[3] = grad[5] = grad[6] = 0.0
            grad[0] = direction * (1.0 - decay)
            grad[1] = direction * decay
            grad[4] = 0.0
            target = direction * (Fc + drop * decay) + sign_v * sigma * power
            z = s * abs(x[g, i] - x_r)
            if z >= 1.0:
                shape, slope = 1.0, 0.0
            elif z > 0.0:
                shape, slope = z * (1.0 - math.log(z)), -math.log(z)
            else:
                shape, slope = 0.0, 0.0
            F = F_r + (target - F_r) * shape
            for j in range(7):
                last[j] = grad_r[j] * (1.0 - shape) + grad[j] * shape
            last[4] += (target - F_r) * slope * z  # ∂z/∂ln s = z
            F_last = F
            top = max(top, abs(F))
            if w > 0:
                for a in range(p):
                    la = w * last[columns[a]]
                    for b in range(a, p):
                        acc[a, b] += la * last[columns[b]]
        for a in range(p):
            for b in range(a, p):
                info[q, g, a, b] = acc[a, b]
                info[q, g, b, a] = acc[a, b]
        peak[q, g] = top


def _branch_times(amplitude, omega, reach_lo, reach_hi, half):
    """Times of one branch's samples from its reversal: geometric in the distance
    travelled over the presliding arc, and uniform in phase over the whole branch; the
    branch lasts a quarter period (the virgin branch, ``half`` False) or a half period."""
    end = (np.pi if half else np.pi / 2) / omega
    span = 2 * amplitude if half else amplitude
    arc_end = min(reach_hi, span)
    arc = np.geomspace(min(reach_lo, 0.5 * arc_end), arc_end, ARC_POINTS)
    # distance travelled → time: half: A(1 − cos ωτ); virgin: A·sin ωt
    if half:
        phase = np.arccos(np.clip(1 - arc / amplitude, -1, 1))
    else:
        phase = np.arcsin(np.clip(arc / amplitude, -1, 1))
    # the arc resolves (E6') right after the reversal; the uniform points the rest,
    # and the whole branch when it never leaves presliding
    # (a time twice over stands for no time: the same count of samples per branch)
    uniform = np.linspace(0.0, end, REST_POINTS + 1)[1:]
    return np.sort(np.concatenate([phase / omega, uniform]))


def sine_samples(amplitude, frequency, duration, sample_rate, noise, shortest, longest):
    """The samples of a sine record the information is summed over: positions,
    velocities, directions and the recorded samples each stands for (÷σ²), for the
    quarter period from rest and two half periods, the second counted once for each
    half period that follows in ``duration`` (a sample once more where the record
    ends inside a half period after it).

    Parameters
    ----------
    amplitude, frequency : float
        A [m] and f [Hz].
    duration, sample_rate : float
        The record's length [s] and samples per second [Hz].
    noise : float
        Standard deviation of one sample of F [N].
    shortest, longest : float
        The shortest and the longest presliding distance 1/s of the draws [m].
    """
    omega = 2 * np.pi * frequency
    A = amplitude
    reach_lo, reach_hi = ARC_START * shortest, ARC_REACH * longest
    t_quarter = _branch_times(A, omega, reach_lo, reach_hi, half=False)
    t_half = _branch_times(A, omega, reach_lo, reach_hi, half=True)
    # half periods after the first quarter: whole ones, and the start of one more
    halves = max((duration - 0.25 / frequency) * 2 * frequency, 1.0)
    whole = math.floor(halves)
    repeats = (whole - 1) + (t_half < (halves - whole) * 0.5 / frequency)

    def spacing(t, start):
        edges = np.concatenate([[start], 0.5 * (t[1:] + t[:-1]), [t[-1]]])
        return np.diff(edges)

    x = np.concatenate([A * np.sin(omega * t_quarter), A * np.cos(omega * t_half),
                        -A * np.cos(omega * t_half)])
    v = np.concatenate([A * omega * np.cos(omega * t_quarter), -A * omega * np.sin(omega * t_half),
                        A * omega * np.sin(omega * t_half)])
    d = np.concatenate([np.ones(t_quarter.size), -np.ones(t_half.size), np.ones(t_half.size)])
    dt = np.concatenate([spacing(t_quarter, 0.0), spacing(t_half, 0.0),
                         spacing(t_half, 0.0) * repeats])
    return x, v, d, dt * sample_rate / noise**2


class Sine:
    """One position sine record through presliding and reversals."""

    name = "sine"
    depends = ("Fc", "Fs", "V", "delta", "s", "sigma", "n")
    header = ("t", "x")
    #: the limits its runs are bound by
    limits = ("u_max", "v_max", "travel", "duration", "sample_rate")

    def candidates(self, P, setting, middle: int = 0) -> Candidates:
        """Amplitudes from a fifth of the shortest presliding distance to half the
        travel, frequencies from two periods per record to the fastest that keeps the
        peak speed 2π·f·A below ``v_max`` and twenty samples per period."""
        lim = setting.limits
        shortest, longest = 1.0 / np.max(P["s"]), 1.0 / np.min(P["s"])
        top = lim.travel / 2 if lim.travel is not None else LARGEST_AMPLITUDE * longest
        bottom = min(SMALLEST_AMPLITUDE * shortest, top)
        side = max(int(round(math.sqrt(setting.grid))), 2)
        amplitude = np.unique(np.geomspace(bottom, top, side))
        f_lo = MIN_PERIODS / lim.duration
        f_hi = min(lim.sample_rate / MIN_SAMPLES_PER_PERIOD, lim.v_max / (2 * np.pi * bottom))
        if f_hi <= f_lo:
            return Candidates({}, (
                f"no frequency gives {MIN_PERIODS:g} periods within {lim.duration:.3g} s and "
                f"keeps the peak speed below v_max = {lim.v_max:.3g} {setting.units['v']} "
                f"at {MIN_SAMPLES_PER_PERIOD} samples per period"))
        frequency = np.geomspace(f_lo, f_hi, side)
        A, f = (a.ravel() for a in np.meshgrid(amplitude, frequency, indexing="ij"))
        fits = 2 * np.pi * f * A <= lim.v_max * (1 + 1e-12)
        return Candidates({"amplitude": A[fits], "frequency": f[fits]})

    def information(self, cands: Candidates, P, setting, names, middle: int = 0) -> Information:
        lim = setting.limits
        shortest, longest = 1.0 / np.max(P["s"]), 1.0 / np.min(P["s"])
        samples = [sine_samples(A, f, lim.duration, lim.sample_rate, setting.noise,
                                shortest, longest)
                   for A, f in zip(cands.points["amplitude"], cands.points["frequency"])]
        x, v, d, weight = (np.ascontiguousarray(np.stack(part)) for part in zip(*samples))
        with np.errstate(divide="ignore"):
            log_speed = np.log(np.abs(v))
        theta = np.column_stack([np.ravel(np.broadcast_to(P[name], np.shape(P["Fc"])))
                                 for name in PARAMETERS])
        columns = np.array([PARAMETERS.index(name) for name in names], dtype=np.int64)
        info = np.zeros((theta.shape[0], x.shape[0], columns.size, columns.size))
        peak = np.zeros((theta.shape[0], x.shape[0]))
        _sine_information(theta, columns, x, v, log_speed, d, weight, info, peak)
        # a sine that takes more than u_max at the middle draw (the best guess) is not
        # run at all; at another draw, one that does yields nothing there
        usable = (peak <= lim.u_max) & (peak[middle] <= lim.u_max)
        matrix = np.where(usable[..., None, None], info, 0.0)
        return Information(None, matrix, usable, {"peak_force": peak})

    def design(self, counts, cands: Candidates, info: Information, mid: int, setting) -> dict:
        g = int(np.flatnonzero(counts)[0])
        A, f = float(cands.points["amplitude"][g]), float(cands.points["frequency"][g])
        lim = setting.limits
        return {"amplitude": A, "frequency": f, "duration": lim.duration,
                "sample_rate": lim.sample_rate, "periods": f * lim.duration,
                "peak_speed": 2 * np.pi * f * A,
                "peak_force": float(info.predicted["peak_force"][mid, g])}

    def programme(self, design: dict | None, setting, reason: str = "") -> str:
        if not design:
            return empty_csv(self.header, reason)
        return sine_csv(design["amplitude"], design["frequency"], design["duration"],
                        design["sample_rate"], setting.units)


__all__ = ["Sine", "sine_samples"]
