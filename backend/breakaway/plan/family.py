"""What a measurement family is to the planner: a grid of candidate runs within the
rig's limits, the information each run carries about the parameters, and the
programme a rig runs for a chosen design."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Candidates:
    """The runs a design chooses from.

    Attributes
    ----------
    points : dict of numpy.ndarray
        The design variables of each candidate, each of shape (G,) (``k`` for ramps,
        ``v`` for set-points, ``amplitude`` and ``frequency`` for a sine).
    why_none : str or None
        When there is no candidate: why (which limit rules them all out).
    """

    points: dict
    why_none: str | None = None

    @property
    def size(self) -> int:
        return int(next(iter(self.points.values())).size) if self.points else 0


@dataclass
class Information:
    """What each candidate run says about the parameters, at each draw of them.

    Attributes
    ----------
    rows : numpy.ndarray or None
        (Q, G, p): for families whose run is one measurement (up to its sign), the
        Jacobian row divided by the noise, so that the run's Fisher information is
        ``rows[q, g]ᵀ·rows[q, g]``; None otherwise.
    matrix : numpy.ndarray
        (Q, G, p, p): each candidate's Fisher information ``Jᵀ·J/σ²`` at each draw.
    usable : numpy.ndarray
        (Q, G) bool: the run yields its measurement at that draw (a ramp that would
        break away above the force limit, or after the run ends, yields none).
    predicted : dict of numpy.ndarray
        What the run is expected to show, (Q, G) each (``F_ba``, ``F``, peak force, …).
    """

    rows: np.ndarray | None
    matrix: np.ndarray
    usable: np.ndarray
    predicted: dict


def from_rows(partial: dict, names, scale, usable: np.ndarray, predicted: dict) -> Information:
    """The information of runs that are one measurement each: the partial derivatives
    ``partial[name]`` (per unit of the planner's coordinates, ln V and ln s for the
    scales) stacked in ``names`` order and multiplied by ``scale`` (√(measurements)/σ),
    zero where a run yields nothing."""
    rows = np.stack([np.asarray(partial[name], dtype=float) for name in names], axis=-1)
    rows = np.where(usable[..., None], rows * np.asarray(scale)[..., None], 0.0)
    return Information(rows, rows[..., :, None] * rows[..., None, :], usable, predicted)


__all__ = ["Candidates", "Information", "from_rows"]
