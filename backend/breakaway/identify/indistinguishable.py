"""Effects that predict the same data (MODEL.md §7–§8 ``indistinguishable``): the
report names one and gives the other's parameters."""

from __future__ import annotations

import math

from .effects import EFFECTS, viscous_equivalent_of_detection
from .gates import MIN_BIC_DROP
from .warnings import warning


def close_rivals(effect, trial, others, trials) -> list[dict]:
    """``indistinguishable`` for each other passing candidate that explains the data
    almost as well as the accepted ``effect`` (its BIC within MIN_BIC_DROP)."""
    out = []
    for other in others:
        gap = trials[other].bic - trial.bic
        if gap > MIN_BIC_DROP:
            continue
        values = ", ".join(f"{k} = {trials[other].params[k]:.4g}" for k in EFFECTS[other].keys)
        out.append(warning("indistinguishable", other, (
            f"{other} explains these data almost as well as {effect} (its BIC is only "
            f"{gap:.1f} higher; {MIN_BIC_DROP:g} would decide): {effect} is named for "
            f"the lower BIC, the other reading is {other} with {values}")))
    return out


def viscous_or_detection(passing, trials, has_s: bool):
    """MODEL.md §7: on break-away data viscous and detection raise F_ba alike where F̂
    does not vary. When both pass within MIN_BIC_DROP, returns (named, other, warning):
    viscous when the file gives ``# s:``, detection when it does not; else None."""
    if not {"viscous", "detection"} <= set(passing):
        return None
    v, d = trials["viscous"], trials["detection"]
    if abs(v.bic - d.bic) >= MIN_BIC_DROP:
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
        text = (f"viscous and detection predict these break-away data alike; named "
                f"detection because the file gives no '# s:' (σ would scale with an "
                f"arbitrary s). The other reading is σ = {sigma:.4g} {problem.data.unit('N·s/m')} at s = "
                f"{problem.s:g}")
    return named, other, warning("indistinguishable", other, text)


#: ``viscous`` is ``viscous-power`` at n = 1 (MODEL.md §7): never in one model.
EXCLUSIVE = {"viscous": "viscous-power", "viscous-power": "viscous"}
#: ``viscous-power`` is named only when n is this many standard errors from 1.
POWER_SIGMAS = 3.0


def power_is_preferred(power, viscous, heldout_power: float,
                       heldout_viscous: float) -> tuple[bool, str]:
    """MODEL.md §7's rule between ``viscous-power`` and ``viscous`` (fits of each, with
    their held-out errors): the curve is named only when n differs from 1 by more than
    :data:`POWER_SIGMAS` standard errors and both the BIC and the held-out error prefer
    it. Returns the verdict and the sentence that explains it."""
    n, se = power.params["n"], power.stderr.get("n")
    if se is None or not power.determined.get("n", False):
        return False, f"its exponent n = {n:.3g} is not determined by these data"
    distance = abs(n - 1.0) / se
    if distance <= POWER_SIGMAS:
        return False, (f"its exponent n = {n:.3g} ± {se:.2g} is within {POWER_SIGMAS:g} "
                       f"standard errors of 1, where it is viscous")
    if viscous is not None and not power.bic < viscous.bic:
        return False, (f"n = {n:.3g} ± {se:.2g}, but the BIC prefers viscous "
                       f"({viscous.bic:.1f} against {power.bic:.1f})")
    # the named model is the fit to the whole record: its error on new data is not below
    # its error on the record. A held-out error under it came from refits that found a
    # better optimum than the fit the report would name (a viscous fit that bent Fc to
    # its bound to imitate a curve): such a figure does not speak for that fit.
    heldout_power = max(heldout_power, power.rmse)
    if viscous is not None:
        heldout_viscous = max(heldout_viscous, viscous.rmse)
    if not heldout_power < heldout_viscous:
        return False, (f"n = {n:.3g} ± {se:.2g}, but the held-out error prefers viscous "
                       f"({heldout_viscous:.4g} against {heldout_power:.4g} "
                       f"{power.problem.data.unit('N')})")
    return True, (f"n = {n:.3g} ± {se:.2g} differs from 1 by {distance:.0f} standard "
                  f"errors, and the BIC and the held-out error prefer the curve")


__all__ = ["EXCLUSIVE", "POWER_SIGMAS", "close_rivals", "power_is_preferred",
           "viscous_or_detection"]
