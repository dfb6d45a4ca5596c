"""Whether a fit shows an effect's size (the judgement's second rule, :mod:`.judgement`).

An effect is shown where at least one of its size parameters is determined (by the
report's rule, or tied only through a correlation with another parameter, so that the
data determine a combination of the two), describes a part of the curve the data show,
stands clear of the base parameter it differs from (an asymmetry's second level more
than :data:`DIFFERENCE_SIGMAS` standard errors from the first) and differs by more than
where the two directions happen to break away (two Stribeck levels, each shown at one
end of a seal's travel).
"""

from __future__ import annotations

import math

from .effects import EFFECTS
from .fitting import FitResult


def unshown(trial: FitResult, new, beyond) -> list[str]:
    """The effects of ``new`` none of whose sizes ``trial`` shows: determined, within
    the data (``beyond``: :func:`.warnings.beyond_data.beyond_data`), apart from the
    base parameter it differs from and not only where the directions break away
    apart."""
    return [e for e in new if not any(
        _sized(trial, k) and k not in beyond
        and _apart(trial, k, EFFECTS[e].differs_from.get(k))
        and not _placed(trial, k, EFFECTS[e].differs_from.get(k))
        for k in EFFECTS[e].size_keys)]


def _sized(fit: FitResult, key: str) -> bool:
    """Whether ``fit`` determines ``key`` as a size: by the report's rule, or tied only
    through a correlation with another parameter (the data then determine a combination
    of the two, and the effect's force is there: σ·v beside Fc on strokes of one speed)."""
    if fit.determined.get(key):
        return True
    return (fit.assessment.why.get(key) or "").startswith("correlated:")


#: A level of its own beside a base parameter shows an effect only where their
#: difference lies more than this many standard errors from 0.
DIFFERENCE_SIGMAS = 2.0


def difference_stderr(fit: FitResult, key: str, base: str) -> float | None:
    """The standard error of ``key − base`` in ``fit`` (None where ``key`` has none); a
    base the fit holds or ties counts as exact."""
    a = fit.assessment
    se = fit.stderr.get(key)
    if se is None:
        return None
    names = list(a.names)
    se_base = fit.stderr.get(base) if base in names else None
    if se_base is None or a.correlation is None:
        return se
    r = float(a.correlation[names.index(key), names.index(base)])
    r = r if math.isfinite(r) else 0.0
    return math.sqrt(max(se**2 + se_base**2 - 2.0 * r * se * se_base, 0.0))


def _apart(fit: FitResult, key: str, base: str | None) -> bool:
    """Whether ``key`` stands clear of ``base`` (:data:`DIFFERENCE_SIGMAS`): an
    asymmetry whose negative Coulomb level is determined at the positive one's value
    and whose other level is not determined shows no asymmetry. True without a base."""
    if base is None:
        return True
    se = difference_stderr(fit, key, base)
    gap = abs(fit.params[key] - fit.params[base])
    return se is None or gap > DIFFERENCE_SIGMAS * se


#: The Stribeck levels: the peak friction each direction shows where it breaks away.
STRIBECK_LEVELS = ("Fs", "Fs_neg")


def _placed(fit: FitResult, key: str, base: str | None) -> bool:
    """Whether ``key``'s difference from ``base`` is one of place as much as of
    direction: two Stribeck levels, where each direction breaks away at one place of
    its own
    (:meth:`~.models.timeseries.TimeseriesProblem.breakaways_apart`: a seal drawn end
    to end, whose squeeze differs at the two ends)."""
    return base is not None and key in STRIBECK_LEVELS and base in STRIBECK_LEVELS \
        and fit.problem.breakaways_apart(fit.params)


#: How a parameter came out not determined, in words.
_WHY = {"at-bound": "on a bound of its range", "flat": "along a flat direction of the fit",
        "relative": "a standard error larger than its value",
        "artefact": "a standard error too small to be real"}


def why_unshown(fit: FitResult, keys, beyond, differs=None) -> str:
    """Why ``fit`` does not show the sizes ``keys`` (``differs``: each key's base
    parameter), in words, one reason a key."""
    reasons = []
    unit = fit.problem.data.unit("N")
    for key in keys:
        if key in beyond and fit.determined.get(key):
            reasons.append(f"{key} describes a part of the curve the data never show")
            continue
        base = (differs or {}).get(key)
        if base and _sized(fit, key) and not _apart(fit, key, base):
            gap = fit.params[key] - fit.params[base]
            reasons.append(f"{key} − {base} = {gap:.3g} {unit} ± "
                           f"{difference_stderr(fit, key, base):.2g} {unit}, within "
                           f"{DIFFERENCE_SIGMAS:g} standard errors of 0")
            continue
        if _sized(fit, key) and _placed(fit, key, base):
            reasons.append(f"{key} and {base} are shown only where the two directions "
                           f"break away, each at one place of its own (the ends of the "
                           f"travel), so their difference may be one of position")
            continue
        why = fit.assessment.why.get(key) or ""
        text = (f"tied to {why.split(':', 1)[1]}" if why.startswith("correlated:")
                else _WHY.get(why, "not determined"))
        reasons.append(f"{key} {text}")
    return "; ".join(reasons)


__all__ = ["DIFFERENCE_SIGMAS", "STRIBECK_LEVELS", "difference_stderr", "unshown",
           "why_unshown"]
