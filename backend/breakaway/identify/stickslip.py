"""Stick-slip in a time series.

A drive pulls the body through something elastic (a spring, a belt, a compliant
joint); with friction that falls with speed the body sticks while the load builds up,
slips when it breaks away, and sticks again. The velocity itself then alternates
between rest and fast slips, and the force oscillates with that cycle. Over a
one-direction travel the oscillation repeats every distance the body slips, so it fits
a position ripple as well as it fits anything: it is the stick-slip cycle, not
friction locked to position.

A record sticks and slips when, along a short-window velocity:

- the body is at rest (below :data:`REST_SHARE` of its slip speed) for at least
  :data:`MIN_REST_SHARE` of the record, in :data:`MIN_CYCLES` or more stick phases;
- its slips go the same way (:data:`SAME_WAY` of them): a record that turns at its stops
  is strokes, not stick-slip;
- the load rises in the drive's direction during most sticks (:data:`RISING_STICKS`),
  by more than the force's noise: a body held by friction while a drive winds up,
  not one stopped by its drive.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .local_fits import local_fit

#: Samples of the velocity's local fit (short: a slip lasts a few tens of samples).
WINDOW = 9
#: The slip speed is this percentile of the speeds.
SLIP_PERCENTILE = 99.0
#: At rest below this share of the slip speed ...
REST_SHARE = 0.05
#: ... for at least this share of the record ...
MIN_REST_SHARE = 0.3
#: ... in at least this many stick phases (each of at least MIN_STICK_SAMPLES).
MIN_CYCLES = 4
MIN_STICK_SAMPLES = 5
#: Share of the slips that go the drive's way.
SAME_WAY = 0.8
#: Share of the sticks in which the load rises the drive's way by more than the noise.
RISING_STICKS = 0.75
#: From median absolute deviation to standard deviation (Gaussian).
_MAD_TO_STD = 1.4826


@dataclass(frozen=True)
class StickSlip:
    """The stick-slip cycle of a record."""

    cycles: int  # stick phases followed by a slip
    period: float  # median time from one slip to the next [s]
    travel: float  # median distance slipped per cycle [m]
    rest_share: float  # share of the record at rest
    load_rise: float  # median rise of the force over a stick [N]

    def matches(self, wavelength: float, tolerance: float = 0.25) -> bool:
        """Whether a position period ``wavelength`` [m] is the cycle's travel (or a
        whole multiple or fraction of it, up to 3)."""
        for k in (1, 2, 3):
            for period in (self.travel * k, self.travel / k):
                if abs(wavelength - period) <= tolerance * period:
                    return True
        return False


def _runs(mask):
    """(start, stop) of each run of True in ``mask``."""
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def find_stick_slip(t, x, F) -> StickSlip | None:
    """The stick-slip cycle of a record (see the module docstring), or None.

    Parameters
    ----------
    t, x, F : array_like
        Times [s], positions [m] and measured forces [N] of a time series.
    """
    t, x, F = (np.asanyarray(a, dtype=float) for a in (t, x, F))
    if x.size < 10 * WINDOW:
        return None
    speed = np.abs(local_fit(t, x, WINDOW)[0])
    slip_speed = float(np.percentile(speed, SLIP_PERCENTILE))
    drive = np.sign(x[-1] - x[0])
    if not slip_speed > 0 or drive == 0:
        return None
    rest = speed < REST_SHARE * slip_speed
    sticks = [(a, b) for a, b in _runs(rest) if b - a >= MIN_STICK_SAMPLES]
    # a stick counts when a slip follows it
    sticks = [(a, b) for a, b in sticks if b < x.size]
    if len(sticks) < MIN_CYCLES or np.mean(rest) < MIN_REST_SHARE:
        return None
    onsets = np.array([b for _, b in sticks])
    slipped = np.diff(x[np.append(onsets, x.size - 1)])
    if np.mean(np.sign(slipped) == drive) < SAME_WAY:
        return None
    noise = _MAD_TO_STD * float(np.median(np.abs(np.diff(F, 2)))) / math.sqrt(6)
    rises = np.array([drive * (np.median(F[b - 3:b]) - np.median(F[a:a + 3])) for a, b in sticks])
    if np.mean(rises > 3 * max(noise, 1e-12)) < RISING_STICKS:
        return None
    return StickSlip(cycles=len(sticks), period=float(np.median(np.diff(t[onsets])))
                     if onsets.size > 1 else math.nan,
                     travel=float(np.median(np.abs(slipped))), rest_share=float(np.mean(rest)),
                     load_rise=float(np.median(rises)))


__all__ = ["StickSlip", "find_stick_slip"]
