"""Where the parameters are taken to be: one point where the data determine them,
and a few values across the range the data leave open where they do not.

A parameter the data do not determine has no current value to design at. The plan is
made for all the values in its open range at once (the information averaged over the
draws: a pseudo-Bayesian design), and its predicted standard errors are given at each
of a few values across the range. The draws are every combination of the open
parameters' levels.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

#: Levels across an open range: more for the scales, whose range spans decades.
LEVELS = {"V": 5, "s": 5}
DEFAULT_LEVELS = 3
#: With more combinations than this, every open parameter gets three levels.
MAX_DRAWS = 125


@dataclass
class Draws:
    """The parameter values the plan is made for.

    Attributes
    ----------
    P : dict of numpy.ndarray
        Every parameter's value at each draw, shape (Q, 1).
    levels : dict of numpy.ndarray
        The values of each open parameter.
    middle : int
        The draw with every open parameter at its middle level.
    across : dict of list of int
        For each open parameter, the draws with it at each of its levels and the other
        open parameters at their middle levels.
    """

    P: dict
    levels: dict
    middle: int
    across: dict

    @property
    def count(self) -> int:
        return int(np.shape(next(iter(self.P.values())))[0])

    def at(self, q: int) -> dict:
        """The parameter values of draw ``q``."""
        return {name: float(value[q, 0]) for name, value in self.P.items()}


def _spaced(low: float, high: float, count: int) -> np.ndarray:
    if count == 1:
        return np.array([math.sqrt(low * high) if low > 0 else 0.5 * (low + high)])
    return np.geomspace(low, high, count) if low > 0 else np.linspace(low, high, count)


def open_levels(pieces, count: int, centre: float | None = None) -> np.ndarray:
    """``count`` values across the pieces [(low, high), …] of an open range (a range
    on both sides of the data has two), shared out among the pieces, the first getting
    the most: geometric for positive pieces, else linear. With a ``centre`` inside a
    single piece (the value the fit extrapolates to), the middle level is that value."""
    if centre is not None and len(pieces) == 1 and pieces[0][0] < centre < pieces[0][1] \
            and count >= 3:
        low, high = pieces[0]
        side = count // 2 + 1
        return np.concatenate([_spaced(low, centre, side), _spaced(centre, high, side)[1:]])
    out = []
    for i, (low, high) in enumerate(pieces):
        share = max(-(-(count - len(out)) // (len(pieces) - i)), 1)  # ceiling of what is left
        out.extend(_spaced(low, high, share))
    return np.asarray(out, dtype=float)


def make_draws(values: dict, ranges: dict, centres: dict | None = None,
               coarse: bool = False) -> Draws:
    """The draws over the open ``ranges`` (name → list of (low, high) pieces), the other
    parameters at their ``values``; a parameter with a ``centres`` entry (a loosely
    determined one: its estimate) has that as its middle level. ``coarse``: three
    levels each (a quick look, as when asking which family would do)."""
    names = [name for name in ranges]
    counts = [LEVELS.get(name, DEFAULT_LEVELS) for name in names]
    if coarse or int(np.prod(counts)) > MAX_DRAWS:
        counts = [DEFAULT_LEVELS] * len(names)
    levels = {name: open_levels(ranges[name], count, (centres or {}).get(name))
              for name, count in zip(names, counts)}
    grid = list(itertools.product(*(range(c) for c in counts))) or [()]
    Q = len(grid)
    P = {name: np.full((Q, 1), float(value)) for name, value in values.items()}
    for j, name in enumerate(names):
        P[name] = np.array([[levels[name][combo[j]]] for combo in grid])
    centre = tuple(c // 2 for c in counts)
    middle = grid.index(centre)
    across = {}
    for j, name in enumerate(names):
        across[name] = [grid.index(centre[:j] + (level,) + centre[j + 1:])
                        for level in range(counts[j])]
    return Draws(P, levels, middle, across)


__all__ = ["DEFAULT_LEVELS", "Draws", "LEVELS", "MAX_DRAWS", "make_draws", "open_levels"]
