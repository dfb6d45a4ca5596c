"""What a fit determines: standard errors and ``determined`` flags.

A parameter is not determined when it sits on a bound of its range, when it moves along
a flat direction of the fit (a near-zero singular value of the column-scaled Jacobian),
when its relative standard error exceeds 1, or when it is correlated above 0.99 with
another parameter (unless the residual is white and the fit's profile bears the
standard error out: :mod:`.profile`).

Standard errors stay valid when the model is wrong. The textbook ``s²·(JᵀJ)⁻¹`` holds for
white residuals; on a real machine the residual is mostly what the model lacks, smooth
along the record, and it understates the error many times over (a quantised encoder's
turns, an out-of-library presliding shape). So each variance is the larger of that and
the block-robust sandwich ``A⁻¹·(Σ_b g_b·g_bᵀ)·A⁻¹`` (``A = JᵀJ``, ``g_b = J_bᵀ·r_b`` over
contiguous blocks of the rows along the kind's regressor, each as long as the
residual's correlation time): a parameter the data fix holds in every block, one that
follows a misfit does not. A finite standard error below 1e-9 of the value is a numerical
artefact (a Jacobian column that rounding left almost empty), never a result: it is
reported as not determined, with no standard error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: Relative standard error above which a parameter is not determined.
MAX_RELATIVE_ERROR = 1.0
#: Correlation above which two parameters are not separately determined.
MAX_CORRELATION = 0.99
#: Singular values of the column-scaled Jacobian below this share of the largest span
#: a flat direction.
FLAT_SINGULAR_VALUE = 1e-7
#: A standard error below this share of its value is a numerical artefact.
ARTEFACT_RELATIVE_ERROR = 1e-9
#: θ within this share of its range from a bound sits on it.
BOUND_TOLERANCE = 1e-6
#: ... where a range counts as at most this many times the value wide.
WIDE_RANGE = 1e4


@dataclass
class Assessment:
    """Standard errors, flags and reasons for every parameter of a fit.

    ``stderr[name]`` is a float, or None where the data give none (flat, at a bound,
    artefact, held fixed); ``why[name]`` is None for a determined parameter, else a short
    reason: ``"at-bound"``, ``"flat"``, ``"relative"``, ``"correlated:<other>"``,
    ``"artefact"`` or ``"fixed"``. ``correlated[name]`` says, for a parameter not
    determined only through its correlation with another, what the data do determine:
    ``{"with": other, "r": correlation, "slope": c, "stderr": e}``, the combination
    ``name − c·other`` known to ``± e`` (``c = r·σ/σ_other``, ``e = σ·√(1 − r²)``: the
    parameter's error with the other held at its value).
    """

    stderr: dict
    determined: dict
    why: dict
    bound: dict  # name -> "lower" / "upper" for parameters on a bound
    correlated: dict = field(default_factory=dict)
    #: the fitted parameters' correlation matrix, rows and columns in ``names`` order
    #: (NaN where a parameter has no variance); what a plan of the next experiment
    #: adds its information to
    names: tuple = ()
    correlation: np.ndarray | None = None
    #: standard errors in the fit's coordinates where they differ from the parameter's
    #: own: the gap Fs − Fc of a Stribeck level carried above its Coulomb level
    gap_stderr: dict = field(default_factory=dict)
    #: the textbook ``s²·(JᵀJ)⁻¹`` standard errors, before the block-robust sandwich
    #: widens them: what the fit's curvature alone promises (:mod:`.profile`)
    classic_stderr: dict = field(default_factory=dict)


#: The residual's correlation time is summed until its autocorrelation falls below this.
CORRELATION_CUTOFF = 0.05
#: Blocks are at most this share of the rows long (at least ten blocks).
MAX_BLOCK_SHARE = 0.1


def correlation_time(residual) -> int:
    """Rows over which a residual stays correlated: 1 + 2·Σ ρ_k over the lags until the
    autocorrelation ρ_k first falls below :data:`CORRELATION_CUTOFF` (1 for white
    noise)."""
    r = np.asanyarray(residual, dtype=float) - np.mean(residual)
    n = r.size
    if n < 4 or not np.any(r):
        return 1
    size = 1 << int(2 * n - 1).bit_length()
    spectrum = np.fft.rfft(r, size)
    acf = np.fft.irfft(spectrum * np.conj(spectrum), size)[:n]
    acf = acf / acf[0]
    below = np.flatnonzero(acf[1:] < CORRELATION_CUTOFF)
    last = int(below[0]) if below.size else n - 1
    return max(1, int(round(1.0 + 2.0 * float(np.sum(acf[1:last + 1])))))


def block_covariance(J, residual, order=None) -> np.ndarray:
    """The block-robust sandwich "meat" ``Σ_b g_b·g_bᵀ`` of a least-squares fit,
    ``g_b = J_bᵀ·r_b`` over contiguous blocks of the rows in ``order``, each as long as
    the residual's correlation time (:func:`correlation_time`)."""
    J = np.asarray(J, dtype=float)
    r = np.asarray(residual, dtype=float)
    if order is not None:
        r = r[order]
    n = r.size
    length = int(np.clip(correlation_time(r), 1, max(1, int(MAX_BLOCK_SHARE * n))))
    starts = np.arange(0, n, length)
    # a column at a time: a long record's n×p products would each be another copy of J
    scores = np.column_stack([
        np.add.reduceat((column if order is None else column[order]) * r, starts)
        for column in J.T])
    return scores.T @ scores


def assess(problem, theta, jac, cost, n, active_mask=None, residual=None,
           order=None) -> Assessment:
    """Assess a least-squares solution ``theta`` of ``problem`` on ``n`` rows.

    Parameters
    ----------
    problem : Problem
    theta : numpy.ndarray
        Solution in the fit's coordinates.
    jac : numpy.ndarray
        Jacobian of the residuals with respect to θ at the solution, shape (n, p).
    cost : float
        Half the residual sum of squares.
    n : int
        Rows fitted.
    active_mask : numpy.ndarray, optional
        ``least_squares``' active bounds (−1 lower, 1 upper, 0 free).
    residual : numpy.ndarray, optional
        The residuals at the solution, shape (n,); with them the variances are never
        below the block-robust sandwich's (see the module docstring).
    order : numpy.ndarray, optional
        The rows in the order along which the residual is smooth (the kind's
        regressor); the given order by default.
    """
    names = problem.names
    p = len(names)
    params = problem.to_params(theta)
    stderr, determined, why, bound, correlated = {}, {}, {}, {}, {}
    for name in problem.all_names:
        if name not in names:
            stderr[name], determined[name], why[name] = None, False, "fixed"
    if p == 0:
        return Assessment(stderr, determined, why, bound, {})

    lo, hi = problem.bounds()
    span = np.where(np.isfinite(hi - lo), hi - lo, 1.0)
    # a range many decades wider than the value (σ of σ·|v|ⁿ, whose bound must hold n = 3
    # at slow speeds) would call a clear value "on its bound": such a range counts as
    # wide as a few decades of the value (a level's gap above its base keeps its range)
    plain = np.array([not problem.spec(name).log and not problem._gap_base(name)
                      for name in names])
    scale = np.maximum(np.abs(theta), np.abs(lo))
    span = np.where(plain & (scale > 0), np.minimum(span, WIDE_RANGE * scale), span)
    at_lo = theta <= lo + BOUND_TOLERANCE * span
    at_hi = theta >= hi - BOUND_TOLERANCE * span
    if active_mask is not None:
        at_lo |= np.asarray(active_mask) < 0
        at_hi |= np.asarray(active_mask) > 0

    J = np.asarray(jac, dtype=float)
    s2 = 2.0 * cost / max(n - p, 1)
    norms = np.sqrt(np.einsum("ij,ij->j", J, J))  # no n×p square on a long record
    biggest = float(norms.max()) if norms.size else 0.0
    empty = ~(norms > 1e-14 * biggest) if biggest > 0 else np.ones(p, dtype=bool)
    cov = np.full((p, p), np.nan)
    curvature = np.full((p, p), np.nan)
    flat = empty.copy()
    live = np.flatnonzero(~empty)
    if live.size:
        Js = J[:, live] / norms[live]
        # QR's R has the same S and Vt: its SVD spares a long record's n×p U
        _, S, Vt = np.linalg.svd(np.linalg.qr(Js, mode="r"))
        keep = S > FLAT_SINGULAR_VALUE * S[0]
        if not keep.all():
            # parameters with weight in a flat direction are not determined
            weight = np.max(np.abs(Vt[~keep]), axis=0)
            flat[live[weight > 0.1]] = True
        inv = (Vt[keep].T / S[keep] ** 2) @ Vt[keep]
        scaled = inv / np.outer(norms[live], norms[live])  # (JᵀJ)⁺ on the live columns
        classic = scaled * s2
        curvature[np.ix_(live, live)] = classic
        if residual is not None:
            robust = scaled @ block_covariance(J[:, live], residual, order) @ scaled
            # each variance the larger of the two, correlations kept from the classic
            ratio = np.sqrt(np.maximum(np.diag(robust), np.diag(classic))
                            / np.where(np.diag(classic) > 0, np.diag(classic), 1.0))
            classic = classic * np.outer(ratio, ratio)
        cov[np.ix_(live, live)] = classic

    # to the parameters' own units (log scale, Fs carried above Fc)
    G = np.zeros((p, p))
    for i, name in enumerate(names):
        G[i, i] = params[name] if problem.is_log(name) else 1.0
        gap = problem._gap_base(name)
        if gap:
            G[i, names.index(gap)] = 1.0
    gap_stderr = {name: math.sqrt(cov[i, i]) for i, name in enumerate(names)
                  if problem._gap_base(name) and np.isfinite(cov[i, i]) and cov[i, i] > 0}
    cov_p = G @ np.nan_to_num(cov) @ G.T
    var = np.diag(cov_p)
    textbook = np.diag(G @ np.nan_to_num(curvature) @ G.T)
    classic_stderr = {name: math.sqrt(textbook[i]) for i, name in enumerate(names)
                      if textbook[i] > 0}
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov_p / np.sqrt(np.outer(var, var))

    for i, name in enumerate(names):
        value = params[name]
        se = math.sqrt(var[i]) if var[i] > 0 and not flat[i] else None
        reason = None
        if at_lo[i] or at_hi[i]:
            reason = "at-bound"
            bound[name] = "lower" if at_lo[i] else "upper"
            se = None
        elif flat[i] or se is None:
            reason, se = "flat", None
        elif se < ARTEFACT_RELATIVE_ERROR * abs(value):
            reason, se = "artefact", None
        elif problem.spec(name).relative and se > MAX_RELATIVE_ERROR * abs(value):
            reason = "relative"
        else:
            others = [j for j in range(p) if j != i and not flat[j]
                      and np.isfinite(corr[i, j]) and abs(corr[i, j]) > MAX_CORRELATION
                      and not _power_law(problem, name, names[j])]
            if others:
                j = others[0]
                reason = f"correlated:{names[j]}"
                r = float(corr[i, j])
                correlated[name] = {"with": names[j], "r": r, "slope": float(cov_p[i, j] / var[j]),
                                    "stderr": se * math.sqrt(max(0.0, 1.0 - r * r))}
        stderr[name] = se
        determined[name] = reason is None
        why[name] = reason
    return Assessment(stderr, determined, why, bound, correlated, tuple(names), corr,
                      gap_stderr, classic_stderr)


def _power_law(problem, a: str, b: str) -> bool:
    """Whether ``a`` and ``b`` are the exponent and the scale of one power law, whose
    correlation is the unit's, not the data's (:attr:`~.effects.Param.exponent_of`)."""
    return problem.spec(a).exponent_of == b or problem.spec(b).exponent_of == a


__all__ = ["Assessment", "MAX_CORRELATION", "MAX_RELATIVE_ERROR", "assess", "block_covariance",
           "correlation_time"]
