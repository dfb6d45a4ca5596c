"""``ripple``: position-dependent friction A·sin(2πx/λ + φ)."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..residuals import correlation
from .base import MIN_RIPPLE_PERIODS, Effect, Param, _fmt


class Ripple(Effect):
    name = "ripple"
    kinds = ("timeseries",)
    off = {"A": 0.0}
    params = (Param("A", "N", lambda sc: (0.0, 10 * sc.force)),
              # the travel must hold two wavelengths (else the short-travel warning)
              Param("wavelength", "m",
                    lambda sc: (2 * sc.step, sc.travel / MIN_RIPPLE_PERIODS), log=True),
              Param("phase", "rad", lambda sc: (-4 * math.pi, 4 * math.pi), relative=False))
    description = "position-dependent friction A·sin(2πx/λ + φ)"
    regressor = {"timeseries": "x"}
    acts_through = "x"

    def unavailable(self, pb):
        if pb.scales.travel < 8 * MIN_RIPPLE_PERIODS * pb.scales.step:
            return "short-travel: the travel holds too few position steps for a ripple"
        return None

    def sensor(self, pb, p, F, ctx):
        return F + p["A"] * np.sin(2 * np.pi * pb.x / p["wavelength"] + p["phase"])

    def unresolved(self, pb, params):
        """Friction locked to position repeats wherever the body is: a ripple must be
        the stick-slip cycle's travel nowhere (nor shorter than twice it: the body rests
        only that far apart) and hold its wavelength and phase in both halves of the
        travel."""
        lam = params["wavelength"]
        cycle = pb.stick_slip
        if cycle is not None and cycle.matches(lam):
            length = pb.data.unit("m")
            return (f"stick-slip: its wavelength {lam:.3g} {length} is the distance the body "
                    f"slips per stick-slip cycle ({cycle.travel:.3g} {length}): the force oscillates with "
                    f"the cycle, not with the position")
        if cycle is not None and lam < 2 * cycle.travel:
            # the body rests (and the force is read at rest) only every cycle's travel:
            # the rest positions sample x too coarsely for a shorter period (Nyquist)
            return (f"stick-slip: its wavelength {lam:.3g} is shorter than twice the "
                    f"distance the body slips per cycle ({cycle.travel:.3g}); the record "
                    f"holds the body only at positions that far apart, too few to resolve "
                    f"a period that short")
        ripple = params["A"] * np.sin(2 * np.pi * pb.x / lam + params["phase"])
        own = pb.measured - pb.predict(params) + ripple  # what the ripple took
        middle = 0.5 * (float(np.min(pb.x)) + float(np.max(pb.x)))
        halves = [pb.x < middle, pb.x >= middle]
        found = [_local_ripple(pb.x[h], own[h], lam) for h in halves]
        if any(f is None for f in found):
            return None
        (lam_a, phase_a), (lam_b, phase_b) = found
        gap = abs(math.remainder(phase_a - phase_b, 2 * math.pi))
        if abs(lam_a / lam_b - 1) > HALF_WAVELENGTH_TOLERANCE or gap > HALF_PHASE_TOLERANCE:
            return (f"it does not hold across the travel: the two halves of x give "
                    f"wavelengths {lam_a:.3g} and {lam_b:.3g} {pb.data.unit('m')}, phases {phase_a:+.2f} and "
                    f"{phase_b:+.2f} rad")
        return None

    def refuse(self, pb, residual):
        lam = long_wavelength(pb, residual)
        if lam is None:
            return None
        length = pb.data.unit("m")
        return (f"short-travel: the residual's dependence on x is strongest at a wavelength "
                f"of about {lam:.3g} {length}, but the travel ({pb.scales.travel:.3g} {length}) holds fewer "
                f"than {MIN_RIPPLE_PERIODS:g} such periods")

    def starts(self, pb, current, r):
        """Wavelengths of the strongest periodogram peaks of the residual against x."""
        x = pb.x
        travel, step = pb.scales.travel, pb.scales.step
        top = travel / MIN_RIPPLE_PERIODS
        wavelengths = np.geomspace(min(max(4 * step, travel / 2000), top / 2), top, 600)
        power = periodogram(x, r, wavelengths)
        starts = []
        for idx in np.argsort(power)[::-1][:40]:
            lam = wavelengths[idx]
            if any(abs(math.log(lam / s["wavelength"])) < 0.05 for s in starts):
                continue
            phase = 2 * np.pi * x / lam
            basis = np.column_stack([np.sin(phase), np.cos(phase)])
            (c_sin, c_cos), *_ = np.linalg.lstsq(basis, r, rcond=None)
            starts.append({"A": float(math.hypot(c_sin, c_cos)), "wavelength": float(lam),
                           "phase": float(math.atan2(c_cos, c_sin))})
            if len(starts) == 3:
                break
        return starts

    def signature(self, pb, r, params):
        lam = params.get("wavelength")
        if lam is None:
            return "the residual is periodic in x"
        phase = 2 * np.pi * pb.x / lam
        c = math.hypot(correlation(r, np.sin(phase)), correlation(r, np.cos(phase)))
        return (f"the residual is periodic in x with wavelength {_fmt(lam)} {pb.data.unit('m')} "
                f"(correlation {c:.2f} with a sinusoid of x)")


#: The two halves of the travel must agree on the wavelength to this share ...
HALF_WAVELENGTH_TOLERANCE = 0.08
#: ... and on the phase at the fitted wavelength to this [rad].
HALF_PHASE_TOLERANCE = 0.6


def _local_ripple(x, r, wavelength):
    """The wavelength near ``wavelength`` (within 15 %) at which ``r`` is most periodic
    in ``x``, and the phase at ``wavelength`` itself; None for too few rows."""
    if x.size < 20:
        return None
    grid = wavelength * np.linspace(0.85, 1.15, 31)
    best = float(grid[int(np.argmax(periodogram(x, r, grid)))])
    phase = 2 * np.pi * x / wavelength
    basis = np.column_stack([np.sin(phase), np.cos(phase), np.ones_like(x)])
    (c_sin, c_cos, _), *_ = np.linalg.lstsq(basis, r, rcond=None)
    return best, float(math.atan2(c_cos, c_sin))


def long_wavelength(pb, r):
    """The wavelength at which ``r`` depends most on x when that is too long for the
    travel to hold two periods (else None)."""
    travel, step = pb.scales.travel, pb.scales.step
    short = np.geomspace(max(4 * step, travel / 2000), travel / MIN_RIPPLE_PERIODS, 200)
    long = np.geomspace(travel / MIN_RIPPLE_PERIODS, 4 * travel, 60)
    p_long = periodogram(pb.x, r, long)
    if p_long.max() <= periodogram(pb.x, r, short).max():
        return None
    return float(long[int(np.argmax(p_long))])


@njit(cache=True)
def _lomb_scargle(x, y, omegas):
    """Lomb–Scargle power of ``y`` sampled at ``x``, at angular frequencies ``omegas``:
    ``(Σ y·cos ω(x−τ))²/(2 Σ cos² ω(x−τ)) + (Σ y·sin ω(x−τ))²/(2 Σ sin² ω(x−τ))`` with
    ``tan 2ωτ = Σ sin 2ωx / Σ cos 2ωx``, the power of
    :func:`scipy.signal.lombscargle`. One sine and cosine per sample and frequency: the
    sums at the phase offset τ follow from those at 0 by the angle-addition formulas,
    where scipy evaluates every sine and cosine again at ω(x − τ), on dense
    rows × frequencies arrays."""
    n = x.size
    out = np.empty(omegas.size)
    tiny = 1.1102230246251565e-16  # the float's epsneg: no division by a rounded zero
    for k in range(omegas.size):
        cc = cs = yc = ys = 0.0
        for i in range(n):
            c, s = math.cos(omegas[k] * x[i]), math.sin(omegas[k] * x[i])
            cc += c * c
            cs += c * s
            yc += y[i] * c
            ys += y[i] * s
        ss = n - cc
        tau = 0.5 * math.atan2(2.0 * cs, cc - ss)
        ct, st = math.cos(tau), math.sin(tau)
        yc_tau, ys_tau = yc * ct + ys * st, ys * ct - yc * st
        cc_tau = ct * ct * cc + 2.0 * ct * st * cs + st * st * ss
        ss_tau = n - cc_tau
        out[k] = 0.5 * (yc_tau**2 / max(cc_tau, tiny * n) + ys_tau**2 / max(ss_tau, tiny * n))
    return out


def periodogram(x, r, wavelengths):
    """Lomb–Scargle power of ``r`` against ``x`` at ``wavelengths`` (long records are
    subsampled: the cost is rows × wavelengths)."""
    stride = max(1, x.size // 4000)
    x, r = np.asanyarray(x, dtype=float), np.asanyarray(r, dtype=float)
    return _lomb_scargle(np.ascontiguousarray(x[::stride]),
                         np.ascontiguousarray(r[::stride] - r.mean()),
                         np.ascontiguousarray(2 * np.pi / np.asanyarray(wavelengths, dtype=float)))
