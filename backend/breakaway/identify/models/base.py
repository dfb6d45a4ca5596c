"""The kind-independent part of a forward model: :class:`Problem` (the θ ↔ params map
with bounds and transforms from each parameter's
:class:`~breakaway.identify.effects.Param`) and the data's :class:`Scales`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..csvdata import Dataset
from ..effects import EFFECTS, param_spec


@dataclass(frozen=True)
class Scales:
    """Typical magnitudes of a dataset, used for bounds and starting values."""

    force: float  # [N]
    speed: float  # [m/s]
    travel: float = 1.0  # peak-to-peak x [m] (timeseries)
    duration: float = 1.0  # [s] (timeseries)
    accel: float = 1.0  # [m/s²]
    step: float = 1.0  # median |Δx| while moving [m] (timeseries)
    dwell: float = 0.0  # largest dwell [s] (breakaway)
    rate: float = 1.0  # largest k [N/s] (breakaway)


def _robust_scale(values) -> float:
    """A typical magnitude: the 95th percentile of |values| (1 if that is 0)."""
    scale = float(np.percentile(np.abs(values), 95))
    return scale if scale > 0 else 1.0


class Problem:
    """A dataset bound to a set of effects: prediction and the θ ↔ params map.

    Parameters
    ----------
    data : Dataset
        Parsed measurement (:mod:`breakaway.identify.csvdata`).
    effects : sequence of str
        Names from :data:`breakaway.identify.effects.EFFECTS`.
    fixed : dict, optional
        Parameters held at the given values (left out of θ), e.g. a profiled play.
    ties : dict, optional
        Coulomb levels held equal to their Stribeck level (``{"Fc": "Fs"}``): the model
        without a Stribeck drop. By default only a level-only problem ties them.
    """

    kind: str = ""
    base_names: tuple[str, ...] = ()
    #: only the level is determined: Fc is tied to Fs (and Fc_neg to Fs_neg)
    level_only: bool = False

    def __init__(self, data: Dataset, effects=(), fixed=None, ties=None):
        self.data = data
        unknown = [e for e in effects if e not in EFFECTS]
        if unknown:
            raise KeyError(f"unknown effect {unknown[0]!r}: expected one of {', '.join(EFFECTS)}")
        #: in the order they were added; the hooks run in library order
        self.effects = tuple(effects)
        order = list(EFFECTS)
        self.effect_objects = [EFFECTS[e] for e in sorted(effects, key=order.index)]
        self.fixed = dict(fixed or {})
        names = list(self.base_names)
        for effect in self.effect_objects:
            names.extend(effect.keys)
        self.all_names = tuple(names)
        unknown = set(self.fixed) - set(names)
        if unknown:
            raise ValueError(f"cannot fix {sorted(unknown)}: not parameters of this model")
        if ties is not None:
            self.tied = dict(ties)
        else:
            self.tied = {"Fc": "Fs", "Fc_neg": "Fs_neg"} if self.level_only else {}
        self.names = tuple(n for n in names if n not in self.fixed and n not in self.tied)

    # -- θ ↔ params ----------------------------------------------------------------
    def spec(self, name):
        """The :class:`~breakaway.identify.effects.Param` of one of this model's keys."""
        return param_spec(name, self.effects)

    def _gap_base(self, name):
        base = self.spec(name).gap_of
        return base if base in self.names else None

    def to_theta(self, params: dict) -> np.ndarray:
        theta = []
        for name in self.names:
            value = params[name]
            spec = self.spec(name)
            gap = self._gap_base(name)
            if gap:
                value = params[name] - params[gap]
            elif spec.log:
                value = math.log(value)
            theta.append(value)
        return np.clip(np.array(theta, dtype=float), *self.bounds())

    def to_params(self, theta) -> dict:
        p = {}
        for name, value in zip(self.names, np.asarray(theta, dtype=float)):
            p[name] = math.exp(value) if self.spec(name).log else float(value)
        for name in self.names:
            gap = self._gap_base(name)
            if gap:
                p[name] += p[gap]
        for low, level in self.tied.items():
            if level in p:
                p[low] = p[level]
        p.update(self.fixed)
        return {name: p[name] for name in self.all_names}

    def breakaways_apart(self, params) -> bool:
        """Whether the two directions break away only at separate places (a time series
        turning at the ends of its travel): a difference of their Stribeck levels is
        then one of place as much as of direction. False for curves and break-away
        series, whose levels are each direction's own."""
        return False

    def stop_rows(self, params) -> np.ndarray | None:
        """Rows where the body may have halted and turned unseen under ``params`` (a
        time series on an encoder); None where there are none."""
        return None

    def bounds(self):
        lo, hi = [], []
        for name in self.names:
            spec = self.spec(name)
            if spec.gap_of and not self._gap_base(name):
                spec = self.spec(spec.gap_of)  # a tied level: bounded like the base level
            a, b = spec.bounds(self.scales)
            if spec.log:
                a, b = math.log(a), math.log(b)
            lo.append(a)
            hi.append(b)
        return np.array(lo, dtype=float), np.array(hi, dtype=float)

    def is_log(self, name) -> bool:
        return self.spec(name).log

    # -- the model ------------------------------------------------------------------
    def _levels(self, p, negative):
        Fc, Fs = p["Fc"], p["Fs"]
        for effect in self.effect_objects:
            Fc, Fs = effect.levels(self, p, Fc, Fs, negative)
        return Fc, Fs

    def predict(self, params: dict) -> np.ndarray:
        """Predicted measured force for every row [N]."""
        raise NotImplementedError

    # -- what the effects, the noise floor and the report ask of the data -------------
    def sliding_rows(self):
        return np.ones(self.data.n, dtype=bool)

    def direction_counts(self):
        """(rows moving positive, rows moving negative, rows considered), or None."""
        d = self.signed_direction()
        return int(np.count_nonzero(d > 0)), int(np.count_nonzero(d < 0)), int(d.size)

    @property
    def negative_rows(self):
        return self.signed_direction() < 0

    def curve_speeds(self, params: dict) -> np.ndarray:
        """The speeds [m/s] at which the data show the steady curve g(v) (E2): where
        they hold information on Fc, Fs, V and δ."""
        raise NotImplementedError

    def held_force(self, params: dict) -> tuple[float, float] | None:
        """The largest friction [N] the data hold without gross sliding in the positive
        and in the negative direction (lower bounds on Fs and its negative-direction
        level), or None where the kind has no presliding."""
        return None

    def variables(self) -> dict[str, np.ndarray]:
        """The regressors a residual can depend on."""
        raise NotImplementedError
