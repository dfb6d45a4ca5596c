"""The held-out error on blocks of the record: each block's rows are predicted by the
model fitted without them.

The blocks (:func:`heldout_blocks`):

- a time series is cut into :data:`BLOCKS` contiguous blocks of whole strokes (the rows
  between two reversals), grouped to similar sizes: a block then holds what a stroke
  holds, a reversal with its presliding and the sliding after it. Where the record has
  too few strokes for that (a ramp, a one-direction run), the blocks are stretches of
  equal length in time. A long record screened on blocks (:mod:`.screening`) keeps its
  screening blocks;
- steady and break-away rows are separate measurements: the rows, in order of speed (or
  rate), are dealt to the blocks in turn, so that each block spans the whole range.

The refit without a block starts at the fit on every row and takes Gauss–Newton steps
with that fit's Jacobian (:attr:`~.fitting.FitResult.jac`) on the remaining rows (the
chord method): one step is the exact refit of a model linear in its parameters, and a
few bring a nonlinear one close. Each step costs one evaluation of the model instead of
a finite-difference Jacobian's ``p + 1``, so every block of every candidate is refitted.
A direction the remaining rows do not determine (a block that held all of one
direction's sliding) is not moved: the minimum-norm step leaves it where the whole
record put it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .fitting import FitResult, refit, row_scales, weighted_rms

#: Blocks a record is cut into (at least 5; fewer only for very short records).
BLOCKS = 10
#: The fewest rows a block holds (a shorter record has fewer blocks, never below 3).
MIN_BLOCK_ROWS = 2
#: A time series needs this many strokes per block before blocks follow the strokes.
STROKES_PER_BLOCK = 2
#: Chord steps of each refit without a block.
CHORD_STEPS = 3
#: Halvings of a chord step that raises the error on the kept rows before it is given up.
HALVINGS = 4
#: Singular values of the column-scaled Jacobian below this share of the largest span
#: directions the remaining rows do not determine: a step along them is the noise
#: divided by a near-zero singular value (a Coulomb and a Stribeck level that only their
#: sum is seen moved apart by thousands), not a refit.
RCOND = 1e-5


def heldout_blocks(problem) -> list[np.ndarray]:
    """The blocks of :mod:`.heldout` for ``problem``'s rows (indices, each sorted)."""
    n = problem.data.n
    if problem.kind == "timeseries":
        segments = list(problem.data.segments)
        if len(segments) + 1 >= 5:
            edges = [0, *segments, n]
            return [np.arange(a, b) for a, b in zip(edges[:-1], edges[1:])]
        count = _block_count(n)
        starts = np.flatnonzero(np.diff(problem.d) != 0) + 1  # first row of each stroke
        if starts.size + 1 >= STROKES_PER_BLOCK * count:
            # cut at the stroke boundary nearest to each equal share of the rows
            wanted = np.arange(1, count) * n / count
            after = np.searchsorted(starts, wanted).clip(1, starts.size - 1)
            nearer = np.abs(starts[after - 1] - wanted) <= np.abs(starts[after] - wanted)
            cuts = np.unique(np.where(nearer, starts[after - 1], starts[after]))
            edges = [0, *cuts.tolist(), n]
        else:
            edges = np.linspace(0, n, count + 1).round().astype(int).tolist()
        return [np.arange(a, b) for a, b in zip(edges[:-1], edges[1:]) if b > a]
    count = _block_count(n)
    order = np.argsort(problem.regressor_speed(), kind="stable")
    return [np.sort(order[i::count]) for i in range(count)]


def _block_count(n: int) -> int:
    return int(min(BLOCKS, max(3, n // MIN_BLOCK_ROWS)))


@dataclass
class HeldOut:
    """Each row's held-out residual [N] (predicted by the model fitted without its
    block) and the blocks."""

    residual: np.ndarray
    blocks: list

    def sse(self, weights=None) -> np.ndarray:
        """Each block's held-out squared error [N²], rows weighted by ``weights``."""
        r2 = self.residual**2 if weights is None else weights * self.residual**2
        return np.array([float(np.sum(r2[b])) for b in self.blocks])

    @property
    def rmse(self) -> float:
        return math.sqrt(float(np.mean(self.residual**2)))

    def weighted_rmse(self, weights=None) -> float:
        """The held-out RMSE [N] with the rows weighted by ``weights`` (plain for None)."""
        return weighted_rms(self.residual, weights)


def heldout_error(fit: FitResult, blocks) -> HeldOut:
    """Each row's error under ``fit``'s model refitted without the row's block.

    Parameters
    ----------
    fit : FitResult
        A fit on every row.
    blocks : list of numpy.ndarray
        :func:`heldout_blocks`.
    """
    problem = fit.problem
    if fit.jac is None or fit.rows is None or fit.rows.size != problem.data.n:
        fit = refit(problem.data, fit, max_nfev=1)  # the Jacobian on every row
    J, theta0 = np.asarray(fit.jac, dtype=float), fit.theta
    lo, hi = problem.bounds()
    span = np.where(np.isfinite(hi - lo), hi - lo, 1.0)
    free = (theta0 > lo + 1e-9 * span) & (theta0 < hi - 1e-9 * span)
    measured = problem.measured
    n = measured.size
    # the refit minimises what the fit did: the rows' weighted residuals (the Jacobian
    # is theirs); each row's held-out residual is given unweighted
    scales = np.broadcast_to(row_scales(problem.data, np.arange(n)), (n,))
    start = _residual(problem, theta0, measured) * scales
    held = np.empty(n)
    for block in blocks:
        keep = np.ones(n, dtype=bool)
        keep[block] = False
        theta, r = theta0.copy(), start
        Jk = J[keep][:, free]
        scale = np.sqrt(np.sum(Jk * Jk, axis=0))
        scale[scale == 0] = 1.0
        for _ in range(CHORD_STEPS if free.any() else 0):
            step, *_ = np.linalg.lstsq(Jk / scale, -r[keep], rcond=RCOND)
            step = step / scale
            # where the model bends within a step (a steep δ, a parameter near its
            # bound) a shorter step along the same direction still lowers the error
            # on the kept rows; a block that could not move its fit at all would be
            # scored in-sample, to the favour of the larger model
            for _ in range(HALVINGS + 1):
                moved = theta.copy()
                moved[free] = np.clip(theta[free] + step, lo[free], hi[free])
                r_moved = _residual(problem, moved, measured) * scales
                if np.all(np.isfinite(r_moved)) and \
                        np.dot(r_moved[keep], r_moved[keep]) < np.dot(r[keep], r[keep]):
                    break
                step = step / 2
            else:
                break  # no shorter step helps: keep the better point
            theta, r = moved, r_moved
        held[block] = r[block] / scales[block]
    return HeldOut(held, list(blocks))


def _residual(problem, theta, measured):
    """Predicted minus measured F at ``theta`` (the sign least squares minimises)."""
    return problem.predict(problem.to_params(theta)) - measured


__all__ = ["BLOCKS", "CHORD_STEPS", "HALVINGS", "HeldOut", "heldout_blocks", "heldout_error"]
