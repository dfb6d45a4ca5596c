"""Whether a correlated parameter's standard error holds along the fit's valley.

A correlation above 0.99 (:data:`~.identifiability.MAX_CORRELATION`) says that the fit
has a long, narrow valley, not that the data leave a parameter free: the marginal
standard error already is the valley's length, as far as the fit's curvature near the
optimum tells it. What the correlation does put in doubt is that curvature: along a
valley the cost may flatten out (a concave |v|ⁿ trading with Fc at slow speeds) and the
true interval be much wider than ``± 2·SE``.

That holds only where nothing is left that the model lacks. A misfit moves an estimate
along a valley by many standard errors, in every block alike, so that neither the
sandwich nor a profile can show it (a short record's σ = 90 ± 9 for a truth of 243,
its profile as quadratic as promised): the check is made on a white final residual, or
where what is left lies within the rows' own errors and x's reading sets most of them
(:func:`~.diagnosis.diagnose`), and elsewhere the correlation rule stands.

A misfit that follows none of the record's variables is another matter: mains hum on
the force, a vibration of the frame. Where no smooth function of any variable (x, v, t,
the time since the last reversal, the distance from it, direction) explains
:data:`DISTURBANCE_SHARE` of what the model leaves beyond the rows' expected errors
(:func:`follows_no_variable`), the excess is a disturbance of the force channel, not a
dependence the model lacks, and there is nothing for it to trade along a valley: the
profile is checked as on a white residual. The residual is taken in units of each
row's expected error, as the misfit is: the rows where x's reading leaves the
prediction open (a stroke's turns) lie at the ends of the travel, but they are not a
dependence on x. (Strokes with hum 3.5 times the noise floor: σ = 102 ± 17 N·s/m,
truth 99.8, had been "undetermined" for its correlation with Fc alone; no variable
explained 1.5 % of the residual.)

So the interval is checked where it ends: the parameter is held at ``value ± 2·SE``
and every other parameter refitted (the profile). Where the linearisation holds, the
weighted residual sum of squares rises there by ``(2·SE / SE_classic)²·s²`` (at least
``4·s²``, the 95 % likelihood-ratio threshold, where the sandwich did not widen the
error). A parameter whose profile rises by at least :data:`PROFILE_SHARE` of that on
both sides is determined, correlation or not: the data do fix it, to the standard error
reported. One whose valley flattens stays "correlated" with the combination the data
determine.
"""

from __future__ import annotations

import numpy as np

from .fitting import FitError, FitResult, fit_model

#: The profile is taken at this many standard errors either side ...
PROFILE_STEP = 2.0
#: ... and must rise by at least this share of what the linearisation promises there.
PROFILE_SHARE = 0.5
#: Parameters of a Stribeck drop, whose bounds only say that the data show no drop.
STRIBECK_SHAPE = ("Fs", "Fs_neg", "V", "delta")
#: Evaluations of each profile refit (it starts on the valley's linear prediction).
PROFILE_EVALUATIONS = 40


#: A misfit is a disturbance of the force channel where no variable explains this share
#: of the excess it holds beyond the rows' expected errors.
DISTURBANCE_SHARE = 0.05


def follows_no_variable(structure: list[dict], misfit: float) -> bool:
    """Whether a residual whose rows' misfit is ``misfit`` (in units of their expected
    errors, :func:`.input_error.misfit_ratio`) holds its excess as a disturbance that
    follows none of the record's variables: each share of its variance in
    ``structure`` (:func:`.residuals.residual_structure`) is under
    :data:`DISTURBANCE_SHARE` of the share the excess takes, ``1 − 1/misfit²``."""
    if not structure or not misfit > 1.0:
        return False
    excess = 1.0 - 1.0 / misfit**2
    return all(item["strength"] < DISTURBANCE_SHARE * excess for item in structure)


def _profile_rise(fit: FitResult, name: str, held: float, slopes: dict, rss: float) -> float:
    """How much the weighted RSS rises with ``name`` held at ``held`` and the other
    parameters refitted, starting from the valley's linear prediction."""
    problem = fit.problem
    shift = held - fit.params[name]
    start = {key: value + slopes.get(key, 0.0) * shift for key, value in fit.params.items()}
    # a parameter on a log scale that the valley's line takes through zero (a drop's V
    # whose error is as long as it) starts where the fit left it
    start = {key: fit.params[key] if problem.is_log(key) and not value > 0 else value
             for key, value in start.items()}
    start[name] = held
    # a Coulomb level tied to the level held (no drop) is held with it
    held_too = {low: held for low, level in problem.tied.items() if level == name}
    ties = {low: level for low, level in problem.tied.items() if level != name}
    try:
        profile = fit_model(problem.data, fit.effects, starts=[start], rows=fit.rows,
                            screen=1, max_nfev=PROFILE_EVALUATIONS,
                            fixed={**problem.fixed, name: held, **held_too}, ties=ties or None)
    except (FitError, ValueError):
        return 0.0
    return profile.weighted_rss - rss


def confirm_correlated(fit: FitResult) -> FitResult:
    """``fit`` with each parameter that is not determined only through a correlation
    above 0.99 marked determined where its profile at ``± 2·SE`` rises as its standard
    error promises (the module docstring). The assessment is changed in place."""
    a = fit.assessment
    names = [name for name, why in a.why.items() if why and why.startswith("correlated:")]
    if not names or fit.rows is None or a.correlation is None:
        return fit
    # a valley that runs into a bound (n of |v|ⁿ at its end) would go on past it: held
    # there, the profile rises where the data would not (a drop's V, δ and Fs on their
    # bounds only say there is no drop, and describe nothing)
    if set(a.bound) - set(STRIBECK_SHAPE):
        return fit
    rss = fit.weighted_rss
    dof = max(fit.rows.size - len(a.names), 1)
    s2 = rss / dof
    for name in names:
        se, classic = a.stderr.get(name), a.classic_stderr.get(name)
        if not se or not classic or name not in a.names:
            continue
        i = a.names.index(name)
        # the valley's direction: each parameter's regression on this one
        slopes = {other: float(a.correlation[i, j]) * a.stderr[other] / se
                  for j, other in enumerate(a.names)
                  if other != name and a.stderr.get(other) and np.isfinite(a.correlation[i, j])}
        promised = (PROFILE_STEP * se / classic) ** 2 * s2
        value = fit.params[name]
        held = [value + sign * PROFILE_STEP * se for sign in (-1.0, 1.0)]
        if fit.problem.spec(name).relative and held[0] * held[1] <= 0:
            continue  # an interval across zero: its relative error settles it
        if all(_profile_rise(fit, name, h, slopes, rss) >= PROFILE_SHARE * promised
               for h in held):
            # with the Coulomb level tied to it (no drop: Fc is this level's result)
            for level in [name] + [low for low, tied in fit.problem.tied.items() if tied == name]:
                a.determined[level], a.why[level] = True, None
                a.correlated.pop(level, None)
    return fit


__all__ = ["DISTURBANCE_SHARE", "PROFILE_SHARE", "PROFILE_STEP", "confirm_correlated",
           "follows_no_variable"]
