"""An allowance for a dependence the library lacks (a seal whose friction depends
smoothly on position, a gravity model's error along the travel, a warming machine).

Real records hold structure that no candidate describes. Whether a candidate is
accepted must not depend on whether such structure is also there: judged against a
large unknown, a real effect's gain drowns in the unknown's scatter (it is masked), and
a candidate that imitates part of the unknown gains what the unknown gives it (it is
credited). So where the residual depends on a variable that the model does not use —
the position x, the time t, the time since the last reversal, or the distance from it,
along which (E6') has only its fixed shape — a candidate is judged with the same
allowance for that dependence on both sides: a smooth function of the variable, added
to the force (a sensor's or a gravity model's error) and scaled by the direction of
motion (friction that depends on where the body is), fitted by linear least squares
to what each model leaves.

The allowance is what the candidates leave (:func:`structured_variables` is asked of
the residual with the candidate in the model): a candidate that explains the
dependence itself (an inertia that is the whole of a one-direction run's time
structure) is not judged against an allowance it made unnecessary. A candidate whose
force the allowance could make as well (an inertia on a single-frequency sine, where
a = −ω²·x) cannot be told from the dependence the library lacks
(:func:`indistinguishable_from`): that is what a joint fit of the two determines, not a
correlation of regressors.

The allowance has no constant and no level: those are the model's own (an offset, the
Coulomb level, a direction difference).
"""

from __future__ import annotations

import numpy as np

from .identifiability import MAX_CORRELATION
from .residuals import explained_share

#: A variable holds structure when a smooth function of it explains at least this share
#: of the residual's variance (with chance taken off, :func:`.residuals.explained_share`).
STRUCTURE_SHARE = 0.05
#: Knots of the piecewise-linear functions (at quantiles of the variable).
KNOTS = 8
#: The variables of a time series along which the model has no free function: x and t,
#: which it does not use; the time since the last reversal, which it does not use
#: either ((E6') is rate-independent); and the distance from the last reversal, which
#: it uses only through the fixed shape f(z) of (E4), so that a presliding shape of the
#: machine's own leaves a smooth misfit along it.
UNUSED = ("x", "t", "time since reversal", "x - x_r")


def structured_variables(problem, residual) -> tuple[str, ...]:
    """The dependences of ``residual`` on the unused variables (:data:`UNUSED`): a
    smooth function of the variable (``"x"``), or that function signed by the direction
    of motion (``"±x"``: friction that depends on where the body is), that explains at
    least :data:`STRUCTURE_SHARE` of its variance."""
    if problem.kind != "timeseries":
        return ()
    variables = problem.variables()
    signed = residual * problem.d
    found = []
    for name in UNUSED:
        if explained_share(residual, variables[name]) >= STRUCTURE_SHARE:
            found.append(name)
        if explained_share(signed, variables[name]) >= STRUCTURE_SHARE:
            found.append(SIGNED + name)
    return tuple(found)


#: Marks a dependence signed by the direction of motion.
SIGNED = "±"


def variable_of(dependence: str) -> str:
    """The variable of a dependence of :func:`structured_variables`."""
    return dependence.removeprefix(SIGNED)


def basis(problem, dependences) -> np.ndarray | None:
    """The allowance's columns for ``dependences`` (None for none): hat functions on
    :data:`KNOTS` quantile knots of each variable, times the direction for a signed
    dependence, with the constant and the direction's level projected out."""
    if not dependences:
        return None
    variables = problem.variables()
    d = problem.d.astype(float)
    columns = []
    for dependence in dependences:
        hats = hat_functions(np.asarray(variables[variable_of(dependence)], dtype=float))
        columns.append(hats * d[:, None] if dependence.startswith(SIGNED) else hats)
    H = np.column_stack(columns)
    levels = np.column_stack([np.ones_like(d), d])
    coef, *_ = np.linalg.lstsq(levels, H, rcond=None)
    H = H - levels @ coef
    norms = np.sqrt(np.sum(H * H, axis=0))
    kept = norms > 1e-9 * max(float(norms.max()), 1e-300)
    return H[:, kept] / norms[kept]


def hat_functions(u) -> np.ndarray:
    """Piecewise-linear hat functions on :data:`KNOTS` quantile knots of ``u``."""
    knots = np.unique(np.quantile(u, np.linspace(0.0, 1.0, KNOTS)))
    if knots.size < 2:
        return np.zeros((u.size, 0))
    eye = np.eye(knots.size)
    return np.column_stack([np.interp(u, knots, eye[i]) for i in range(knots.size)])


def residual_without(residual, H) -> np.ndarray:
    """What ``residual`` leaves once the allowance ``H`` is fitted to it."""
    if H is None or H.shape[1] == 0:
        return residual
    coef, *_ = np.linalg.lstsq(H, residual, rcond=None)
    return residual - H @ coef


def indistinguishable_from(fit, keys, H) -> str | None:
    """The first of ``keys`` (a candidate's parameters in ``fit``) that the allowance
    ``H`` could replace: the part of its column of the fit's Jacobian that the model's
    other columns do not explain lies in the span of ``H`` to a correlation above 0.99
    (in a joint fit of the two, that parameter would not be determined). None when
    each is its own."""
    if H is None or fit.jac is None:
        return None
    J = np.asarray(fit.jac, dtype=float)
    if fit.problem.data.weights is not None:
        # the Jacobian is of the weighted residuals: the allowance is weighted alike
        H = H * np.sqrt(fit.problem.data.weights)[:, None]
    names = list(fit.problem.names)
    for key in keys:
        if key not in names:
            continue
        j = names.index(key)
        others = np.delete(J, j, axis=1)
        unique = _left_over(J[:, j], others)
        if _multiple_correlation(unique, _left_over(H, others)) > MAX_CORRELATION:
            return key
    return None


def _left_over(y, X):
    """What the columns ``X`` leave of ``y`` (a vector or columns) by least squares."""
    norms = np.sqrt(np.sum(X * X, axis=0))
    X = X[:, norms > 0] / norms[norms > 0]
    if X.shape[1] == 0:
        return y
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    return y - X @ coef


def _multiple_correlation(y, X) -> float:
    """The correlation of ``y`` with its least-squares fit on the columns ``X``."""
    norms = np.sqrt(np.sum(X * X, axis=0))
    X = X[:, norms > 0] / norms[norms > 0]
    total = float(np.dot(y, y))
    if total <= 0 or X.shape[1] == 0:
        return 0.0
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    left = y - X @ coef
    return float(np.sqrt(max(0.0, 1.0 - float(np.dot(left, left)) / total)))


__all__ = ["KNOTS", "SIGNED", "STRUCTURE_SHARE", "UNUSED", "basis", "indistinguishable_from",
           "residual_without", "structured_variables", "variable_of"]
