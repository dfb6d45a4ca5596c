"""Effects that predict the same data (the warning ``indistinguishable``): the report
names one and gives the other's parameters."""

from __future__ import annotations

import math

from .effects import EFFECTS, param_spec, viscous_equivalent_of_detection
from .fitting import weighted_rmse
from .judgement import MIN_BIC_DROP, MIN_RMSE_GAIN
from .warnings import warning


def close_rivals(effect, trial, others, trials) -> list[dict]:
    """``indistinguishable`` for each other passing candidate that explains the data
    as well as the accepted ``effect`` (their BICs within MIN_BIC_DROP)."""
    out = []
    for other in others:
        gap = trials[other].bic - trial.bic
        if abs(gap) > MIN_BIC_DROP:
            continue
        values = ", ".join(f"{k} = {trials[other].params[k]:.4g}" for k in EFFECTS[other].keys)
        if gap >= 0:
            why = (f"its BIC is only {gap:.1f} higher; {MIN_BIC_DROP:g} would decide): "
                   f"{effect} is named for the lower BIC")
        else:
            why = (f"its BIC is {-gap:.1f} lower, within the {MIN_BIC_DROP:g} that would "
                   f"decide): {effect} is named for its fewer parameters")
        out.append(warning("indistinguishable", other, (
            f"{other} explains these data as well as {effect} ({why}, the other reading "
            f"is {other} with {values}")))
    return out


def like_a_dependence(effect, fit, key, variables) -> dict:
    """``indistinguishable``: ``effect`` was accepted although a smooth dependence on
    ``variables`` (which the library lacks) would predict its ``key`` as well on these
    data (inertia on one sine, where a = −ω²·x): the physical effect is named, and the
    report says that the data do not tell them apart."""
    unit = fit.problem.data.unit(param_spec(key, fit.effects).unit)
    value = f"{fit.params[key]:.4g}" + (f" {unit}" if unit not in ("", "-") else "")
    return warning("indistinguishable", key, (
        f"{effect} is named with {key} = {value}, but on these data a force "
        f"that depends smoothly on {variables} would predict the same: a record with "
        f"other motions (other speeds, amplitudes or frequencies) would tell them apart"))


def viscous_or_detection(passing, trials, has_s: bool):
    """On break-away data viscous and detection raise F_ba alike where F̂
    does not vary. Returns (named, other, warning) when both are candidates: viscous
    when the file gives ``# s:`` and the two fit within MIN_BIC_DROP, detection when it
    gives no s (whatever their BICs: the viscous reading's bend with the rate comes
    from E12 at an s the file does not give, so its better fit is no evidence); else
    None."""
    if not {"viscous", "detection"} <= set(passing):
        return None
    v, d = trials["viscous"], trials["detection"]
    if has_s and abs(v.bic - d.bic) >= MIN_BIC_DROP:
        return None
    problem = v.problem
    named, other = ("viscous", "detection") if has_s else ("detection", "viscous")
    if has_s:
        F_hat = problem.F_hat(v.params["Fc"], v.params["Fs"])
        tau = v.params["sigma"] / viscous_equivalent_of_detection(1.0, problem.s, F_hat) \
            if F_hat > 0 else math.nan
        text = (f"viscous and detection predict these break-away data alike; named viscous "
                f"because the file gives s = {problem.s:g}. The other reading is a "
                f"detection delay tau_det = {tau:.4g} s")
    else:
        F_hat = problem.F_hat(d.params["Fc"], d.params["Fs"])
        sigma = viscous_equivalent_of_detection(d.params["tau_det"], problem.s, F_hat)
        text = (f"viscous and detection both explain how F_ba rises with the rate (alike "
                f"where F̂ does not vary); named detection because the file gives no "
                f"'# s:' (σ, and how the viscous reading bends with the rate, would "
                f"scale with an arbitrary s). The other reading is "
                f"σ = {sigma:.4g} {problem.data.unit('N·s/m')} at s = {problem.s:g}")
    return named, other, warning("indistinguishable", other, text)


#: Pairs never in one model: ``viscous`` is ``viscous-power`` at n = 1; an offset
#: beside an asymmetry adds a fifth parameter to four sliding and stiction levels (a
#: direction's levels move with the offset), so that only the virgin branch of the first
#: stroke could tell their sum apart.
EXCLUSIVE = {"viscous": "viscous-power", "viscous-power": "viscous",
             "offset": "asymmetry", "asymmetry": "offset"}
#: ``viscous-power`` is named only when n is this many standard errors from 1.
POWER_SIGMAS = 3.0
#: What an effect shows beyond a simpler one nested in it (§7): an offset is an
#: asymmetry whose two directions' levels differ by one shift, the Stribeck levels as the
#: Coulomb ones (up to the virgin branch). Its separate Coulomb levels are what the
#: offset's shift gives too; its own content is that the two directions' Stribeck drops
#: differ: the levels (Fs, Fs_neg) that say what each drop is.
NESTED = {("asymmetry", "offset"): (("Fs", "Fc"), ("Fs_neg", "Fc_neg"))}


def beyond_nested(richer: str, simpler: str, fit, beyond=()) -> str | None:
    """Why ``fit`` (with the effect ``richer``) shows nothing beyond the simpler effect
    nested in it (None: it does, or the two are not nested).

    Each direction's drop must be what the data show: its Stribeck level determined, or
    on its Coulomb level's bound (no drop that way), and in neither case among
    ``beyond`` (the names :func:`~.warnings.beyond_data.beyond_data` gives, such as a
    Stribeck level below a force the data hold without sliding: the drop is then at
    least that large, not what the fit says). A drop the data do not resolve is no drop
    (§7b, 5), and two absent drops are the offset's own. Drops that differ where each
    direction breaks away at one place of its own
    (:meth:`~.models.timeseries.TimeseriesProblem.breakaways_apart`) may differ by
    place, not direction."""
    levels = NESTED.get((richer, simpler))
    if levels is None:
        return None
    bound = getattr(getattr(fit, "assessment", None), "bound", {})
    absent = 0
    for level, low in levels:
        if level not in fit.params:
            return f"it has no {level}, so it says nothing that {simpler} does not"
        no_drop = bound.get(level) == "lower" or fit.params[level] <= fit.params[low]
        absent += no_drop
        if level in beyond or not (no_drop or fit.determined.get(level, False)):
            return (f"its {level} = {fit.params[level]:.4g} is not what the data "
                    f"determine, so it says nothing that {simpler} does not")
    if absent == len(levels):
        return f"it has no Stribeck drop either way, so it says nothing that {simpler} does not"
    if fit.problem.breakaways_apart(fit.params):
        return (f"its drops differ where each direction breaks away at one place of its "
                f"own (the ends of the travel), where a stiction that depends on position "
                f"predicts the same, so it says nothing that {simpler} does not")
    return None


def _likelihood_distance(power, viscous) -> float:
    """n's distance from 1 in standard errors by the likelihood ratio of the nested
    fits: the root of ``N·ln(RSS_viscous/RSS_power)``."""
    ratio = math.log(max(viscous.rmse, 1e-300) / max(power.rmse, 1e-300))
    return math.sqrt(max(0.0, 2.0 * power.n * ratio))


def power_is_preferred(power, viscous, heldout_power: float,
                       heldout_viscous: float) -> tuple[bool, str]:
    """The rule between ``viscous-power`` and ``viscous`` (fits of each, with their
    held-out errors, rows weighted as in the fits): the curve is named only when n
    differs from 1 by more than :data:`POWER_SIGMAS` standard errors and both the BIC and
    the held-out error prefer it. Returns the verdict and the sentence that explains it.

    An n on a bound of its range has no standard error; the distance from 1 is then the
    likelihood ratio's: the root of ``N·ln(RSS_viscous/RSS_power)``, which is n's
    distance from 1 in standard errors where both are defined. A curve bent beyond the
    range's end (a rise steeper at low speed than |v|^0.2 makes) is still not straight.
    The same for an n that moves with another parameter (a correlation above 0.99): its
    standard error is the curvature at the optimum, which a long valley need not keep.
    An n the data do not determine otherwise names the straight form; so does a curve
    that lowers the RMSE by less than :data:`~.judgement.MIN_RMSE_GAIN` against it."""
    n, se = power.params["n"], power.stderr.get("n")
    why = power.assessment.why.get("n") or ""
    if why == "at-bound" and viscous is not None:
        distance = _likelihood_distance(power, viscous)
        if distance <= POWER_SIGMAS:
            return False, (f"its exponent n = {n:.3g} sits on a bound of its range, and the "
                           f"straight line fits within {POWER_SIGMAS:g} standard errors of it")
        spread = "(on the bound of its range; its distance from 1 by the likelihood ratio)"
    elif why.startswith("correlated:") and viscous is not None:
        # n moves with another parameter along a long valley, where its standard error
        # (the curvature at the optimum) may not hold far out; whether the curve is
        # straight is the nested models' likelihood ratio, which needs no curvature
        distance = _likelihood_distance(power, viscous)
        other = why.split(":", 1)[1]
        if distance <= POWER_SIGMAS:
            return False, (f"its exponent n = {n:.3g} moves with {other}, and the straight "
                           f"line fits within {POWER_SIGMAS:g} standard errors of the curve")
        spread = f"(moving with {other}; its distance from 1 by the likelihood ratio)"
    else:
        if se is None or not power.determined.get("n", False):
            return False, f"its exponent n = {n:.3g} is not determined by these data"
        distance = abs(n - 1.0) / se
        if distance <= POWER_SIGMAS:
            return False, (f"its exponent n = {n:.3g} ± {se:.2g} is within {POWER_SIGMAS:g} "
                           f"standard errors of 1, where it is viscous")
        spread = f"± {se:.2g}"
    curved, straight = (weighted_rmse(power), weighted_rmse(viscous)) \
        if viscous is not None else (0.0, 0.0)
    if curved > (1 - MIN_RMSE_GAIN) * straight:
        # the curve's exponent is a parameter like an effect's: worth naming where it
        # changes the fit visibly (n = 1.07 ± 0.02, from how a 1 µm scale's counts
        # bend v, is a straight line to any reader); rows weighted as in the fit
        return False, (f"n = {n:.3g} {spread}, but the curve lowers the RMSE by only "
                       f"{100 * (1 - curved / straight):.2g} % against the straight line's")
    if viscous is not None and not power.bic < viscous.bic:
        return False, (f"n = {n:.3g} {spread}, but the BIC prefers viscous "
                       f"({viscous.bic:.1f} against {power.bic:.1f})")
    # the named model is the fit to the whole record: its error on new data is not below
    # its error on the record. A held-out error under it came from refits that found a
    # better optimum than the fit the report would name (a viscous fit that bent Fc to
    # its bound to imitate a curve): such a figure does not speak for that fit.
    heldout_power = max(heldout_power, curved)
    if viscous is not None:
        heldout_viscous = max(heldout_viscous, straight)
    if not heldout_power < heldout_viscous:
        weighted = " (rows weighted as in the fit)" \
            if power.problem.data.weights is not None else ""
        return False, (f"n = {n:.3g} {spread}, but the held-out error{weighted} prefers "
                       f"viscous ({heldout_viscous:.4g} against {heldout_power:.4g} "
                       f"{power.problem.data.unit('N')})")
    return True, (f"n = {n:.3g} {spread} differs from 1 by {distance:.0f} standard "
                  f"errors, and the BIC and the held-out error prefer the curve")


__all__ = ["EXCLUSIVE", "NESTED", "POWER_SIGMAS", "beyond_nested", "close_rivals",
           "like_a_dependence", "power_is_preferred", "viscous_or_detection"]
