"""The design search: which runs, out of the candidates, make the targets' predicted
uncertainty smallest.

The criterion is the volume of the targets' confidence region after the plan, with
the other parameters estimated alongside (D-optimality on the targets), averaged
over the draws of the parameters the data leave open:
``mean_q ln det Σ_q[t, t]``, ``Σ_q = (I_now + Σ_runs I_run,q)⁻¹``. Smaller is better.

Runs that are one measurement each (ramps, set-points) change ``Σ`` by a rank-one
update, so the effect of adding any candidate at any draw is one vectorised formula:
the design is built greedily, then improved by exchanging one run at a time for the
best candidate until no exchange helps (Fedorov's exchange). A record that is one run
(the sine) is chosen among all candidates directly. :func:`exhaustive` scores every
design of a grid, the check the search is measured against.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

#: Passes of the exchange over all runs at most.
EXCHANGE_PASSES = 8
#: An exchange must lower the criterion by at least this much.
EXCHANGE_GAIN = 1e-9


def criterion(information: np.ndarray, targets) -> float:
    """``mean_q ln det Σ_q[t, t]`` for information (Q, p, p)."""
    cov = np.linalg.inv(information)
    block = cov[:, targets][:, :, targets]
    return float(np.mean(np.linalg.slogdet(block)[1]))


def _gains(information: np.ndarray, rows: np.ndarray, targets) -> np.ndarray:
    """The change of the criterion that adding each candidate makes, shape (G,).

    With ``Σ = I⁻¹`` and a run's row ``j``: ``Σ' = Σ − Σj·jᵀΣ/(1 + jᵀΣj)``, so
    ``ln det Σ'[t,t] − ln det Σ[t,t] = ln(1 − aᵀ·Σ[t,t]⁻¹·a/(1 + jᵀΣj))``, ``a = (Σj)[t]``.
    """
    cov = np.linalg.inv(information)  # (Q, p, p)
    inner = np.linalg.inv(cov[:, targets][:, :, targets])  # (Q, t, t)
    spread = np.einsum("qij,qgj->qgi", cov, rows)  # Σj, (Q, G, p)
    scale = 1.0 + np.einsum("qgi,qgi->qg", rows, spread)
    a = spread[..., targets]
    quad = np.einsum("qgi,qij,qgj->qg", a, inner, a) / scale
    return np.mean(np.log(np.clip(1.0 - quad, 1e-300, None)), axis=0)


def _outer(rows: np.ndarray, g: int) -> np.ndarray:
    return rows[:, g, :, None] * rows[:, g, None, :]


def choose_runs(information: np.ndarray, rows: np.ndarray, runs: int, targets) -> np.ndarray:
    """Counts (G,) of each candidate in the design of ``runs`` one-measurement runs.

    Parameters
    ----------
    information : numpy.ndarray
        (Q, p, p) what is known before the plan, at each draw.
    rows : numpy.ndarray
        (Q, G, p) each candidate's noise-scaled Jacobian row at each draw.
    runs : int
    targets : sequence of int
        Indices of the target parameters.
    """
    current = information.copy()
    chosen = []
    for _ in range(runs):
        g = int(np.argmin(_gains(current, rows, targets)))
        chosen.append(g)
        current += _outer(rows, g)
    for _ in range(EXCHANGE_PASSES):
        changed = False
        for i, g in enumerate(chosen):
            without = current - _outer(rows, g)
            gains = _gains(without, rows, targets)
            best = int(np.argmin(gains))
            if gains[best] < gains[g] - EXCHANGE_GAIN:
                chosen[i] = best
                current = without + _outer(rows, best)
                changed = True
        if not changed:
            break
    return np.bincount(np.asarray(chosen, dtype=int), minlength=rows.shape[1])


def choose_one(information: np.ndarray, matrix: np.ndarray, targets) -> np.ndarray:
    """Counts (G,) with a one for the best single record among the candidates, whose
    information is ``matrix`` (Q, G, p, p)."""
    total = information[:, None] + matrix
    cov = np.linalg.inv(total)
    block = cov[..., targets, :][..., :, targets]
    score = np.mean(np.linalg.slogdet(block)[1], axis=0)
    counts = np.zeros(matrix.shape[1], dtype=int)
    counts[int(np.argmin(score))] = 1
    return counts


def exhaustive(information: np.ndarray, rows: np.ndarray, runs: int, targets,
               batch: int = 4096) -> tuple[np.ndarray, float, int]:
    """Every design of ``runs`` runs from the candidates (repeats allowed) scored by
    the criterion: the best counts, its criterion and the number of designs scored."""
    G = rows.shape[1]
    outer = rows[..., :, None] * rows[..., None, :]  # (Q, G, p, p)
    best, best_value, scored = None, math.inf, 0
    designs = itertools.combinations_with_replacement(range(G), runs)
    while True:
        chunk = np.array(list(itertools.islice(designs, batch)), dtype=int)
        if chunk.size == 0:
            break
        total = information[None] + outer[:, chunk].sum(axis=2).transpose(1, 0, 2, 3)
        cov = np.linalg.inv(total)
        block = cov[..., targets, :][..., :, targets]
        score = np.mean(np.linalg.slogdet(block)[1], axis=1)
        i = int(np.argmin(score))
        scored += chunk.shape[0]
        if score[i] < best_value:
            best, best_value = chunk[i], float(score[i])
    return np.bincount(best, minlength=G), best_value, scored


__all__ = ["EXCHANGE_GAIN", "EXCHANGE_PASSES", "choose_one", "choose_runs", "criterion",
           "exhaustive"]
