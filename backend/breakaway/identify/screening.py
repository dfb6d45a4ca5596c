"""Long time series are screened on contiguous blocks spread over the record (each at
the full sampling rate, so reversals and velocities stay resolved); the chosen model is
then refitted on every row."""

from __future__ import annotations

import numpy as np

from .csvdata import Dataset
from .preparation import subset

#: Time series longer than this are screened on a decimated copy of about this size.
SCREEN_ROWS = 20_000
#: ... in this many contiguous blocks.
SCREEN_BLOCKS = 8
#: Function evaluations (each with a finite-difference Jacobian) of a refit on every row
#: from the screened solution: it only polishes.
FULL_REFIT_EVALUATIONS = 8


def needs_screening(data: Dataset) -> bool:
    """Whether ``data`` is a time series long enough to be screened on blocks."""
    return data.kind == "timeseries" and data.n > 1.5 * SCREEN_ROWS


def screening_blocks(data: Dataset, directions=None, rows: int = None,
                     count: int = None) -> Dataset:
    """:data:`SCREEN_BLOCKS` contiguous blocks spread evenly over a long time series,
    :data:`SCREEN_ROWS` rows in all, as independent records: each keeps the full
    sampling (reversals, presliding and velocity stay resolved) and together they
    span the whole duration (a drift stays visible). Given the record's
    ``directions``, each block starts at a motion reversal, where (E6')'s state is
    known: x_r and F_r are the block's first position and measured force."""
    rows = rows or SCREEN_ROWS
    count = count or SCREEN_BLOCKS
    length = rows // count
    starts = np.linspace(0, data.n - length, count).astype(int)
    if directions is not None:
        turns = np.flatnonzero(np.diff(directions) != 0)  # the sample before a reversal
        turns = turns[turns <= data.n - length]
        if turns.size:
            at = np.searchsorted(turns, starts[1:])
            starts[1:] = turns[np.minimum(at, turns.size - 1)]
            starts = np.unique(starts)
            # blocks may not overlap: keep the ones that fit after their predecessor
            kept = [starts[0]]
            for a in starts[1:]:
                if a >= kept[-1] + length:
                    kept.append(a)
            starts = np.array(kept)
    index = np.concatenate([np.arange(a, a + length) for a in starts])
    return subset(data, index, segments=[i * length for i in range(1, starts.size)])


__all__ = ["FULL_REFIT_EVALUATIONS", "SCREEN_BLOCKS", "SCREEN_ROWS", "needs_screening",
           "screening_blocks"]
