"""Whether the data resolve a Stribeck drop; where they do not, the model without it.

No drop, no Stribeck parameters. A drop of g (E2) from Fs to Fc is velocity weakening:
friction that falls as the speed rises. A fit can place one where the data cannot show
it: a few hundredths of a newton at a Stribeck velocity far beyond the fastest speed of
the file, or a "drop" whose fall the viscous rise more than cancels at every measured
speed, bending a rising curve into shape. Such a drop describes nothing the data hold,
and it drags Fc with it (to 0, or to the top of a fall that is never seen). The drop is
unresolved (:func:`unresolved_drop`) when

- Fs − Fc is within :data:`GAP_SIGMAS` standard errors of 0;
- V lies beyond the fastest speed at which the data show the curve, and the part of
  the drop over the speeds they show is within :data:`FALL_NOISE` noise floors;
- V or δ sits on a bound of its range;
- the steady curve with the effects that act on the body does not fall, anywhere over
  the speeds the data show it at, by more than :data:`FALL_NOISE` noise floors.

The first and the last hold a drop that the data show (its level at rest determined, V
within the speeds shown) and that earns its parameters as an effect does: there the
gap's error runs along a trade with the viscous rise, and a curve that only bends is
the note's drop under a rise.

The model is then refitted without the drop (:func:`without_drop`): Fc tied to Fs, V
and δ held. Fc is its result, with its standard error; Fs, V and δ are ``beyond-data``
with the bound the data set.
"""

from __future__ import annotations

import functools

import numpy as np

from ..steady import stribeck_kernel
from .effects import DELTA_BOUNDS
from .fitting import FitResult, fit_model
from .straight import straight_forms

#: A drop within this many standard errors of Fs − Fc = 0 is not resolved.
GAP_SIGMAS = 2.0
#: The steady curve must fall by more than this many noise floors somewhere.
FALL_NOISE = 2.0
#: Speeds at which the steady curve is evaluated between the slowest and the fastest.
CURVE_POINTS = 200
#: Stribeck velocities a trapped drop is fitted again from, spread (geometrically) over
#: the speeds the data show the curve at, each with each shape of :data:`RETRY_SHAPES`.
RETRY_SPEEDS = 5
RETRY_SHAPES = (1.0, 2.0)
#: Retry starts polished (the best by their initial cost).
RETRY_POLISHED = 3
#: A retry starts with each Coulomb level this many times below its Stribeck level.
RETRY_GAP = 1.2
#: Each direction's levels and the parameters of their drop.
LEVELS = (("Fc", "Fs"), ("Fc_neg", "Fs_neg"))


def steady_curve(problem, params: dict, speeds, negative: bool = False) -> np.ndarray:
    """|F| of the steady curve [N] at ``speeds`` [m/s] in one direction: g (E2) with
    the direction's levels plus what the accepted effects add to the body's steady
    force (viscous, viscous-power)."""
    speeds = np.asanyarray(speeds, dtype=float)
    Fc, Fs = problem._levels(params, np.full(speeds.size, negative))
    total = stribeck_kernel(speeds, Fc, Fs, params["V"], params["delta"])
    for effect in problem.effect_objects:
        total = total + effect.target(problem, params, speeds)
    return total


def largest_fall(problem, params: dict, slowest: float, fastest: float) -> float:
    """The largest fall [N] of the steady curve with rising speed between ``slowest``
    and ``fastest`` (either direction): 0 for a curve that never falls."""
    speeds = np.geomspace(slowest, fastest, CURVE_POINTS) if slowest > 0 \
        else np.linspace(0.0, fastest, CURVE_POINTS)
    falls = []
    for negative, (_, level) in zip((False, True), LEVELS):
        if level not in params:
            continue
        curve = steady_curve(problem, params, speeds, negative)
        falls.append(float(np.max(np.maximum.accumulate(curve) - curve)))
    return max(falls, default=0.0)


def _shown_fall(problem, params: dict, slowest: float, fastest: float) -> float:
    """How far g (E2) alone falls [N] between the slowest and the fastest speed the
    data show the curve at (either direction): the part of a drop they hold. A drop
    whose V lies just beyond the fastest speed still falls by half within it."""
    speeds = np.array([slowest, fastest])
    falls = [float(np.subtract(*stribeck_kernel(speeds, *problem._levels(
        params, np.full(2, negative)), params["V"], params["delta"])))
        for negative, (_, level) in zip((False, True), LEVELS) if level in params]
    return max(falls, default=0.0)


def unresolved_drop(fit: FitResult, noise: float, bends: bool = True,
                    earns=None) -> str | None:
    """Why the data do not resolve ``fit``'s Stribeck drop (None: they do, or the
    model has no drop to judge: tied levels, a level-only fit, a record that never
    slides); with ``bends=False``, a drop that only bends a rising curve passes (its
    case is then the judgement's: :func:`retried_drop`).

    A gap Fs − Fc within its standard errors is no drop unless the data show where the
    drop starts and how fast it falls (:func:`_drop_shown`) and it earns its parameters
    beside the model without it: ``earns(without, fit)``, None where it does (with
    ``bends=False`` that is the judgement's to say afterwards). The gap is the drop's
    asymptote: where the viscous rise turns the curve up before the drop levels off,
    its error runs along the trade with σ and V while the fall the data show stands
    clear (a short record's drop fitted at the truth, Fs − Fc = 5.99 ± 4.2 N, its curve
    falling by 0.54 N, four noise floors).

    A drop whose curve never falls over the speeds shown, only bends the rise, is no
    drop on the same terms: unless it is shown and earns its parameters. A bend of the
    rise at low speed is what the note's curve makes of a drop under a viscous rise;
    a curvature of the viscous term that could stand in for it is an effect, which the
    search judged beside the drop, and removing the drop would hand it the bend (one
    plateau speed near V: a drop and a line that the model without the drop missed by
    a BIC of 536, replaced by σ·|v|^2.1 with Fc 26 % high)."""
    problem, p = fit.problem, fit.params
    if problem.tied or "V" not in problem.names or "delta" not in problem.names:
        return None
    speeds = problem.curve_speeds(p)
    if speeds.size == 0:
        return None
    a = fit.assessment
    unit, speed_unit = problem.data.unit("N"), problem.data.unit("m/s")
    gaps = []
    for low, level in LEVELS:
        if level in p:
            gap, se = p[level] - p[low], (a.gap_stderr or {}).get(level)
            gaps.append((level, low, gap, se))
    shown = _drop_shown(fit, [level for level, _, _, _ in gaps], speeds)

    @functools.cache  # a refit without the drop: asked once, and only where needed
    def shown_and_earned() -> bool:
        return shown and earns is not None and earns(without_drop(fit), fit) is None

    if all(se is not None and gap <= GAP_SIGMAS * se for _, _, gap, se in gaps) and not (
            shown and (not bends or shown_and_earned())):
        level, low, gap, se = gaps[0]
        return (f"{level} − {low} = {gap:.3g} {unit} ± {se:.2g} {unit} is within "
                f"{GAP_SIGMAS:g} standard errors of no drop")
    fastest, slowest = float(np.max(speeds)), float(np.min(speeds))
    if p["V"] > fastest and not _shown_fall(problem, p, slowest, fastest) > FALL_NOISE * noise:
        return (f"its Stribeck velocity V = {p['V']:.3g} {speed_unit} lies beyond the "
                f"fastest speed at which the data show the curve ({fastest:.3g} "
                f"{speed_unit}), and the part of the drop over the speeds they show is "
                f"within {FALL_NOISE:g} noise floors")
    if a.bound.get("delta") or p["delta"] <= DELTA_BOUNDS[0] or p["delta"] >= DELTA_BOUNDS[1]:
        return f"its shape δ = {p['delta']:.3g} sits on a bound of its range"
    if a.bound.get("V"):
        # a drop pressed against the slowest Stribeck velocity the range allows is over
        # before any speed the data resolve: neither its speed nor its shape is theirs
        return (f"its Stribeck velocity V = {p['V']:.3g} {speed_unit} sits on a bound of "
                f"its range")
    if bends and problem.kind != "breakaway":
        fall = largest_fall(problem, p, slowest, fastest)
        if not fall > FALL_NOISE * noise and not shown_and_earned():
            return (f"the steady curve never falls with speed over the speeds the data "
                    f"show it at ({slowest:.3g} to {fastest:.3g} {speed_unit}; its largest "
                    f"fall is {fall:.3g} {unit}, within {FALL_NOISE:g} noise floors): "
                    f"the drop only bends the rise of the curve")
    return None


def _drop_shown(fit: FitResult, levels, speeds) -> bool:
    """Whether the data show where ``fit``'s drop starts and how fast it falls: each
    Stribeck level of ``levels`` (the force at rest) determined and within the forces
    the record holds, V within the speeds the data show the curve at (``speeds``), no
    Coulomb level on its bound. Only where the drop would level off may then trade
    with the rest. A V below the slowest speed shown puts the whole fall where the data
    never are, as one beyond the fastest does (a creep record crawling at 0.4–0.7
    mrad/s: V = 2 µrad/s, and a level at rest of 187 N·m in a file whose forces stay
    below 10)."""
    p = fit.params
    largest = float(np.max(np.abs(fit.problem.measured)))
    return not level_on_bound(fit) \
        and float(np.min(speeds)) <= p["V"] <= float(np.max(speeds)) \
        and all(fit.determined.get(level) and p[level] <= largest for level in levels)


def retried_drop(fit: FitResult, noise: float) -> tuple[FitResult, FitResult] | None:
    """``fit``'s effects with a Stribeck drop, fitted from Stribeck velocities spread
    over the speeds the data show the curve at: the best fit whose drop the data
    determine (its gap, V and δ, by :func:`unresolved_drop` with ``bends=False``, and
    no Coulomb level on its bound), with the model without a drop it adds the drop to
    (``fit``, or ``fit`` with a curve in its straight form); or None.

    ``fit`` is the model the search chose without a drop. A drop under a steeper rise
    (a curved viscous term rising fastest at low speed) never makes the curve fall, yet
    it can be there: on a gearbox's steady curve the model without it left 2.5 times
    the error of the one with it, Fc 44 % off. Whether such a drop is kept is the
    judgement's, as for any added parameters; this fit is what it judges.

    A curve of ``fit`` is retried in its straight form too (σ·|v| for σ·|v|ⁿ), and the
    lower BIC of the two is returned: without a drop, the curve's bend can be the drop's
    (a level held flat from rest to the plateau and then rising, |v|³ on a short record
    whose truth is a drop and a line: the drop and the line there lowered the BIC by 578
    against the curve), and beside the drop the curve's exponent, trading with it, can
    leave the drop unresolved where the line does not."""
    origins = [fit] + [line for _, line in straight_forms(fit.problem.data, fit)]
    tried = [(again, origin) for origin in origins
             if (again := _with_drop(origin, noise)) is not None]
    return min(tried, key=lambda pair: pair[0].bic, default=None)


def _with_drop(fit: FitResult, noise: float) -> FitResult | None:
    """``fit``'s effects with a drop fitted afresh (:func:`retried_drop`), where the
    data determine it."""
    problem, p = fit.problem, fit.params
    if "V" not in problem.names and "V" not in problem.fixed:
        return None
    speeds = problem.curve_speeds(p)
    speeds = speeds[speeds > 0]
    if speeds.size == 0:
        return None
    low, high = float(np.min(speeds)), float(np.max(speeds))
    base = {name: value for name, value in problem.fixed.items() if name not in ("V", "delta")}
    start = dict(p)
    for level_low, level in LEVELS:
        if level in start:
            start[level_low] = start[level_low] / RETRY_GAP
    starts = [{**start, "V": float(V), "delta": delta}
              for V in np.geomspace(low, high, RETRY_SPEEDS) for delta in RETRY_SHAPES]
    try:
        again = fit_model(problem.data, fit.effects, starts=starts, screen=RETRY_POLISHED,
                          fixed=base or None)
    except (ValueError, FloatingPointError):
        return None
    if unresolved_drop(again, noise, bends=False) is not None:
        return None
    # a drop that takes a Coulomb level to its bound is the curve's shape, not a level
    # the data show (a robot joint's rise bent by a "drop" from 2.3 N·m to 0)
    if level_on_bound(again):
        return None
    return again


def level_on_bound(fit: FitResult) -> bool:
    """Whether a Coulomb level of ``fit`` (either direction's) ended on its bound: a fit
    that needs that is bending the curve's shape, not reading a level."""
    return any(fit.assessment.bound.get(low) for low, _ in LEVELS if low in fit.params)


def without_drop(fit: FitResult, rows=None) -> FitResult:
    """``fit``'s model refitted without its Stribeck drop: each Coulomb level tied to
    its Stribeck level, V and δ held at their values. Fc takes the level's value,
    standard error and verdict (:func:`.fitting.fit_model`)."""
    problem, p = fit.problem, fit.params
    ties = {low: level for low, level in LEVELS if level in p}
    held = {**problem.fixed, "V": p["V"], "delta": p["delta"]}
    start = dict(p)
    for low, level in ties.items():
        start[level] = start[low] = max(p[low], 0.5 * (p[low] + p[level]))
    return fit_model(problem.data, fit.effects, starts=[start], rows=rows, screen=1,
                     fixed=held, ties=ties)


def drop_bound_text(fit: FitResult, reason: str) -> dict[str, str]:
    """The ``beyond-data`` sentences of a model without its drop: Fs, V and δ of each
    direction describe a drop the data do not hold; the level is a lower bound on Fs."""
    p, unit = fit.params, fit.problem.data.unit("N")
    out = {}
    for low, level in LEVELS:
        if level not in p:
            continue
        text = (f"the data do not resolve a Stribeck drop ({reason}); {low} = "
                f"{p[low]:.4g} {unit} comes from the model without it, and the data set "
                f"only {level} ≥ {p[low]:.4g} {unit} (the sliding level)")
        out.setdefault(level, text)
        out.setdefault("V", text)
        out.setdefault("delta", text)
    return out


__all__ = ["FALL_NOISE", "GAP_SIGMAS", "drop_bound_text", "largest_fall", "level_on_bound",
           "steady_curve", "unresolved_drop", "without_drop"]
