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
                f"arbitrary s). The other reading is σ = {sigma:.4g} N·s/m at s = "
                f"{problem.s:g}")
    return named, other, warning("indistinguishable", other, text)


__all__ = ["close_rivals", "viscous_or_detection"]
