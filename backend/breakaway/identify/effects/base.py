"""The base of the effect library: :class:`Param`, :class:`Effect`, the
base model's parameters and the helpers the effects share."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np


#: The break-away kind's fixed reading of E13: F̂ = avg at z* = 0.95.
BREAKAWAY_Z = 0.95
#: Bounds of the Stribeck exponent in fits (δ > 0, |δ| >= 0.05).
DELTA_BOUNDS = (0.05, 10.0)
#: Share of the moving rows each direction needs before direction effects are tried.
MIN_DIRECTION_SHARE = 0.05
#: ... and at least this many rows.
MIN_ROWS_PER_DIRECTION = 5
#: Distinct rates break-away data need before rate effects (and the Stribeck shape) are
#: determined (else the single-rate warning).
MIN_RATES = 3
#: The travel must hold this many wavelengths of a ripple.
MIN_RIPPLE_PERIODS = 2.0


@dataclass(frozen=True)
class Param:
    """One fitted parameter.

    Attributes
    ----------
    name : str
        The report's key.
    unit : str
        SI unit for linear motion (N, m);
        :func:`~breakaway.identify.csvdata.dataset.unit_of` turns it rotary.
    bounds : callable
        ``bounds(scales) -> (lo, hi)`` in the parameter's own units.
    log : bool
        Carried as its logarithm in the fit (scale parameters over decades).
    gap_of : str or None
        Carried as ``value − params[gap_of] >= 0`` (``Fs`` above ``Fc``).
    profiled : bool
        Switches the model discretely: profiled on a grid, not moved by the Jacobian.
    relative : bool
        Its relative standard error means something (not for an angle).
    exponent_of : str or None
        The exponent of a power law whose scale is ``params[exponent_of]`` (n of
        σ·|v|ⁿ): the two's correlation depends on the unit of the base (σ is the value
        at |v| = 1 of the file's unit), and referred to a speed inside the data it is
        zero, so it never makes either undetermined
        (:func:`~breakaway.identify.identifiability.assess`).
    """

    name: str
    unit: str
    bounds: Callable
    log: bool = False
    gap_of: str | None = None
    profiled: bool = False
    relative: bool = True
    exponent_of: str | None = None


def _level(sc):
    return 1e-9 * sc.force, 20 * sc.force


BASE_PARAMS: dict[str, Param] = {p.name: p for p in (
    Param("Fc", "N", _level),
    Param("Fs", "N", lambda sc: (0.0, 20 * sc.force), gap_of="Fc"),
    # a Stribeck velocity far below every measured speed is not identifiable and is a
    # degenerate basin (g = Fc at any speed but exactly 0)
    Param("V", "m/s", lambda sc: (1e-3 * sc.speed, 1e4 * sc.speed), log=True),
    Param("delta", "", lambda sc: DELTA_BOUNDS),
    Param("s", "1/m", lambda sc: (1e-2 / sc.travel, max(1e3 / sc.step, 1e2 / sc.travel)),
          log=True),
)}


# ---------------------------------------------------------------------------------
# small helpers shared by the effects
# ---------------------------------------------------------------------------------


def _project(r, basis) -> float:
    """Least-squares coefficient of ``r`` on one basis vector."""
    return float(np.dot(r, basis) / max(float(np.dot(basis, basis)), 1e-300))


def _fmt(value) -> str:
    return f"{value:.3g}"


# ---------------------------------------------------------------------------------
# the effect base class
# ---------------------------------------------------------------------------------


class Effect:
    """One effect the base model lacks; subclasses fill in the hooks."""

    name: str = ""
    kinds: tuple[str, ...] = ()
    params: tuple[Param, ...] = ()
    description: str = ""
    #: x-axis of the residual plot that shows the effect, per kind
    regressor: dict[str, str] = {}
    #: the variable the library otherwise lacks that the effect acts through (``t`` for a
    #: drift, ``x`` for a ripple), or None: such an effect is not judged against an
    #: allowance for a dependence on that variable, but must show its own form
    #: (:meth:`unresolved`) instead (:mod:`breakaway.identify.allowance`)
    acts_through: str | None = None
    #: whether the effect's force reads the acceleration taken from x (its resolution
    #: then reaches the prediction twice differentiated)
    reads_acceleration: bool = False
    #: (effect, values): this effect holds ``effect`` as the case ``values`` (a curve
    #: with n = 1 is the straight line), so its fit can start where that one's ended
    extends: tuple[str, dict] | None = None

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.params)

    @property
    def size_keys(self) -> tuple[str, ...]:
        """The parameters that set how large the effect is (not its shape): the ones
        the data must determine for the effect to be shown."""
        return tuple(self.off) or self.keys

    #: the parameter values that switch the effect off (its size is zero)
    off: dict = {}
    #: size keys that are a level of their own beside a base parameter (the negative
    #: direction's Coulomb level beside Fc): the effect's size is their difference,
    #: shown only where it stands clear of 0
    differs_from: dict = {}

    def switched_off(self, params: dict) -> dict:
        """``params`` with this effect switched off (:attr:`off`)."""
        return {**params, **self.off}

    def unavailable(self, pb) -> str | None:
        """Why the data cannot show this effect (None: it can be tried)."""
        return None

    def refuse(self, pb, residual) -> str | None:
        """Why the current residual rules the effect out this round (None: try it)."""
        return None

    def unresolved(self, pb, params: dict) -> str | None:
        """Why the fitted effect lies within what the data cannot resolve (a play
        inside the encoder's resolution, a lag shorter than the velocity's own window),
        so that it cannot be told from how the data were read (None: it can)."""
        return None

    def starts(self, pb, current: dict, residual) -> list[dict]:
        """Starting values of the effect's parameters, read off the current residual."""
        raise NotImplementedError

    def signature(self, pb, residual, params: dict) -> str:
        """One sentence on what in the residual points to this effect."""
        raise NotImplementedError

    # prediction hooks: neutral by default
    def body_motion(self, pb, p, ctx):
        return ctx

    def slip_velocity(self, pb, p, v):
        return v

    def levels(self, pb, p, Fc, Fs, negative):
        return Fc, Fs

    def scale_g(self, pb, p, g):
        return g

    def target(self, pb, p, v):
        return 0.0

    def sensor(self, pb, p, F, ctx):
        return F

    def acceleration_gain(self, pb, p) -> float:
        """How much the predicted force moves per unit of a [N per m/s²] (an effect
        that reads the acceleration: a's error where it jumps reaches the force
        through it)."""
        return 0.0


def _needs_both_directions(pb) -> str | None:
    counts = pb.direction_counts()
    if counts is None:
        return "the file has no direction column"
    pos, neg, total = counts
    need = max(MIN_ROWS_PER_DIRECTION, math.ceil(MIN_DIRECTION_SHARE * total))
    if min(pos, neg) < need:
        return (f"one-direction: {pos} rows move positive and {neg} negative; each "
                f"direction needs at least {need} to separate levels or an offset")
    return None


def _needs_rates(pb) -> str | None:
    if pb.kind == "breakaway" and pb.distinct_rates < MIN_RATES:
        return (f"single-rate: {pb.distinct_rates} distinct rate(s); a rate effect needs "
                f"at least {MIN_RATES}")
    return None


def sliding_unseen(pb, params) -> str | None:
    """Why a record cannot show an effect on the sliding curve (a viscous rise, a drift
    or a lag of g): it never reaches gross sliding, so the curve is never shown. None
    when it does (or the kind has no presliding)."""
    if pb.kind != "timeseries" or pb.curve_speeds(params).size:
        return None
    return ("the record never reaches gross sliding: it never shows the sliding curve "
            "this effect changes")


def _direction_means(pb, r):
    sliding, d = pb.sliding_rows(), pb.signed_direction()
    pos, neg = r[sliding & (d > 0)], r[sliding & (d < 0)]
    return (float(np.mean(pos)) if pos.size else 0.0, float(np.mean(neg)) if neg.size else 0.0)

