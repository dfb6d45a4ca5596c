"""Forward models of the three data kinds with any set of the library's effects.

One :class:`Problem` subclass per kind binds a dataset to a set of effects. The base
class maps between the report's parameter dictionary and the vector θ that
``scipy.optimize.least_squares`` moves (bounds and transforms from each parameter's
:class:`~breakaway.identify.effects.Param`); each kind's ``predict`` runs the model
core's equations — g of (E2) (:func:`breakaway.steady.stribeck_kernel`), (E6')
(:func:`breakaway.presliding._presliding_kernel`), (E12) — and calls each effect's hooks
in a fixed order. :func:`problem_for` picks the class for a dataset.
"""

from __future__ import annotations

import numpy as np

from ..csvdata import Dataset
from ..effects import MIN_RATES
from .base import Problem, Scales
from .breakaway import BreakawayProblem
from .steady import SteadyProblem
from .timeseries import TimeseriesProblem, with_forces, with_weights

PROBLEMS = {cls.kind: cls for cls in (TimeseriesProblem, SteadyProblem, BreakawayProblem)}


def problem_for(data: Dataset, effects=(), fixed=None, ties=None) -> Problem:
    """The :class:`Problem` of ``data``'s kind with ``effects``.

    Break-away data at fewer than three distinct rates get a level-only problem (the
    single-rate warning).
    """
    if data.kind == "breakaway":
        level_only = np.unique(data.columns["k"]).size < MIN_RATES
        return BreakawayProblem(data, effects, fixed, ties, level_only=level_only)
    return PROBLEMS[data.kind](data, effects, fixed, ties)


__all__ = ["BreakawayProblem", "PROBLEMS", "Problem", "Scales", "SteadyProblem",
           "TimeseriesProblem", "problem_for", "with_forces", "with_weights"]
