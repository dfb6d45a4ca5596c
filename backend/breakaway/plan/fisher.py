"""Fisher information: what the existing data hold, what a planned run adds, and what
the identification would call determined afterwards.

The planner works in coordinates in which the parameters' uncertainty is about
symmetric: ``ln V`` and ``ln s`` (scales over decades), the others as they are. The
existing data's information is the inverse of the fit's covariance over the
parameters it determines; a run adds ``Jᵀ·J/σ²``. A weak prior (ten times each
parameter's value, or a thousandfold for the scales) keeps the algebra finite where
nothing is known; it never makes a parameter determined, because alone it leaves a
relative standard error above one.
"""

from __future__ import annotations

import math

import numpy as np

from ..identify.identifiability import MAX_CORRELATION, MAX_RELATIVE_ERROR
from .curve import LOG_PARAMETERS

#: The weak prior's standard deviation: this many times a parameter's value (or its
#: scale), and ln of this factor for the scales V and s.
PRIOR_FACTOR = 10.0
LOG_PRIOR_FACTOR = 1e3


def weak_prior(names, values: dict, force: float, speed: float) -> np.ndarray:
    """Diagonal information (p, p) of the weak prior at the middle of the draws.

    Parameters
    ----------
    names : sequence of str
        The parameters, in the planner's order.
    values : dict of float
        Their values (the middle draw).
    force, speed : float
        Typical force [N] and speed [m/s] (scales of σ = force/speed when σ is 0).
    """
    spread = []
    for name in names:
        if name in LOG_PARAMETERS:
            spread.append(math.log(LOG_PRIOR_FACTOR))
        elif name == "sigma":
            spread.append(PRIOR_FACTOR * max(abs(values[name]), force / speed))
        elif name in ("Fc", "Fs"):
            spread.append(PRIOR_FACTOR * max(abs(values[name]), force))
        else:
            spread.append(PRIOR_FACTOR * max(abs(values[name]), 1.0))
    return np.diag(1.0 / np.square(spread))


def existing_information(names, values: dict, covariance) -> np.ndarray:
    """Information (p, p) the existing data hold on the parameters ``names``.

    ``covariance`` is ``(keys, matrix)`` over the parameters the data give a standard
    error, in their own units (a report's ``final.covariance``), or None. Parameters
    outside it get none: the data leave them wholly open.
    """
    p = len(names)
    out = np.zeros((p, p))
    if covariance is None:
        return out
    keys, matrix = covariance
    shared = [name for name in names if name in keys]
    if not shared:
        return out
    pick = [keys.index(name) for name in shared]
    cov = np.asarray(matrix, dtype=float)[np.ix_(pick, pick)]
    # to the planner's coordinates: d(ln V) = dV/V
    scale = np.array([1.0 / values[name] if name in LOG_PARAMETERS else 1.0 for name in shared])
    cov = cov * np.outer(scale, scale)
    where = [names.index(name) for name in shared]
    out[np.ix_(where, where)] = np.linalg.pinv(cov, hermitian=True)
    return out


def covariance(information: np.ndarray) -> np.ndarray:
    """The covariance (…, p, p) that information (…, p, p) implies."""
    return np.linalg.inv(information)


def verdicts(cov: np.ndarray, names, values: dict):
    """Standard errors in the parameters' own units and whether the identification
    would call each parameter determined (relative standard error at most one, no
    correlation above 0.99 with another).

    Parameters
    ----------
    cov : numpy.ndarray
        (Q, p, p) covariance in the planner's coordinates.
    names : sequence of str
    values : dict of numpy.ndarray
        Each parameter's value at each draw, shape (Q, 1) or scalar.

    Returns
    -------
    stderr : numpy.ndarray
        (Q, p) [the parameter's unit].
    determined : numpy.ndarray
        (Q, p) bool.
    """
    spread = np.sqrt(np.maximum(np.diagonal(cov, axis1=-2, axis2=-1), 0.0))
    value = np.column_stack([np.ravel(np.broadcast_to(values[name], (cov.shape[0], 1)))
                             for name in names])
    log = np.array([name in LOG_PARAMETERS for name in names])
    stderr = np.where(log, spread * np.abs(value), spread)
    relative = np.where(log, spread, stderr / np.where(value != 0, np.abs(value), np.inf))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / (spread[..., :, None] * spread[..., None, :])
    corr = np.where(np.eye(len(names), dtype=bool), 0.0, np.nan_to_num(corr))
    tied = np.max(np.abs(corr), axis=-1) > MAX_CORRELATION if len(names) > 1 else \
        np.zeros_like(relative, dtype=bool)
    return stderr, (relative <= MAX_RELATIVE_ERROR) & ~tied


__all__ = ["LOG_PRIOR_FACTOR", "PRIOR_FACTOR", "covariance", "existing_information",
           "verdicts", "weak_prior"]
