"""The plan of the next experiment: the runs of one family, within the rig's limits,
that determine what the data do not, with the standard errors predicted before and
after, the programme a rig runs, and what no run of the family can do.

Steps: what is known (:mod:`.knowledge`), the limits (:mod:`.limits`), the draws over
the open ranges (:mod:`.draws`), the candidates and their information
(:mod:`.ramps`, :mod:`.setpoints`, :mod:`.sine`, :mod:`.fisher`), the search
(:mod:`.search`), and what a target the plan leaves open needs
(:mod:`.honesty`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from .curve import PARAMETERS, symbol
from .draws import Draws, make_draws
from .family import Candidates, Information
from .fisher import covariance, existing_information, verdicts, weak_prior
from .honesty import not_measured
from .knowledge import Knowledge, PlanError, from_params, from_report
from .limits import resolve_limits
from .ramps import Ramps
from .search import choose_one, choose_runs, criterion
from .setpoints import SetPoints
from .setting import DEFAULT_GRID, DEFAULT_RUNS, Setting
from .sine import Sine
from .words import describe, json_safe

FAMILIES = {family.name: family for family in (Ramps(), SetPoints(), Sine())}
#: The noise assumed without a record, as a share of the Coulomb level.
ASSUMED_NOISE_SHARE = 0.01
#: Candidates of the quick plans that say which other family would determine a target.
QUICK_GRID = 48


@dataclass
class Outcome:
    """One plan's numbers before they are put in words (see :func:`plan_experiment`)."""

    family: object
    setting: Setting
    names: list
    targets: list
    draws: Draws | None
    candidates: Candidates | None
    information: Information | None
    counts: np.ndarray | None
    before: np.ndarray | None
    after: np.ndarray | None
    stderr_after: np.ndarray | None
    determined_after: np.ndarray | None
    notes: list
    dropped: dict
    #: (Q, p, p) what is known before the plan, at each draw
    known: np.ndarray | None = None

    def determined_over_range(self, name: str) -> bool:
        """Whether the plan determines ``name`` at every value across its open range (the
        other open parameters at their middle), or at the middle draw when it is not
        open."""
        draws = self.draws.across.get(name) or [self.draws.middle]
        return bool(np.all(self.determined_after[draws, self.names.index(name)]))


def _noise(knowledge: Knowledge, noise, family: str) -> tuple[float, list[str]]:
    if noise is not None:
        if isinstance(noise, bool) or not isinstance(noise, (int, float)) \
                or not math.isfinite(noise) or noise <= 0:
            raise PlanError(f"noise must be a finite number > 0, got {noise!r}", ("noise",))
        return float(noise), []
    F = knowledge.units["F"]
    if knowledge.noise is not None:
        notes = []
        if family != {"breakaway": "ramps", "steady": "steady",
                      "timeseries": "sine"}[knowledge.kind]:
            notes.append(f"The noise of one measurement is taken as the record's, "
                         f"{knowledge.noise:.3g} {F}; give the noise if this rig's differs for "
                         "this kind of run.")
        return knowledge.noise, notes
    value = ASSUMED_NOISE_SHARE * knowledge.values["Fc"]
    return value, [f"No record gives the noise: {value:.3g} {F} ({100 * ASSUMED_NOISE_SHARE:g} % "
                   "of Fc) is assumed; give the noise of your rig."]


def _parameters(knowledge: Knowledge, family) -> tuple[list, dict]:
    """The parameters the family's measurement depends on that the plan estimates, and
    those it holds as given (with why)."""
    given = dict(knowledge.given)
    if not knowledge.from_data and family.name != "sine" and "s" not in knowledge.ranges:
        given["s"] = "the model's presliding scale: V is meant for this s"
    names = [name for name in family.depends if name not in given]
    if "s" in names and math.isnan(knowledge.values["s"]):
        raise PlanError("a steady record does not hold the presliding scale s, which the "
                        f"{family.name} family depends on: give its range "
                        "(ranges.s = [low, high] in 1/m)", ("ranges", "s"))
    return names, given


def _targets(requested, knowledge: Knowledge, family, names, given) -> tuple[list, dict]:
    """The targets the plan is for, and each requested one it is not for, with why."""
    if requested is None:  # every parameter the data leave open: said of the others
        requested = list(names)
    dropped, chosen = {}, []
    units = knowledge.units
    for i, name in enumerate(requested):
        if name not in PARAMETERS:
            raise PlanError(f"unknown target {name!r}: expected some of {', '.join(PARAMETERS)}",
                            ("targets", i))
        if knowledge.determined.get(name, False):
            se = knowledge.stderr.get(name)
            sym = symbol(name)
            dropped[name] = (f"{sym} is already determined by the data ({sym} = "
                             f"{knowledge.values[name]:.4g} ± {se:.2g} {units.get(name, '')})"
                             .replace(" )", ")") + ": nothing new to measure for it")
            level = "Fs" if name == "Fc" else "Fs_neg" if name == "Fc_neg" else None
            if level and level in knowledge.ranges:
                # the report's Fc is the model's without a drop; a plan that opens the
                # drop estimates Fc beside Fs, V and δ, with the larger model's error
                dropped[name] += (f"; that standard error is the model's without a "
                                  f"Stribeck drop, and after a plan that opens the drop "
                                  f"{sym} is estimated beside it (its standard error there "
                                  f"is the larger model's)")
        elif name in given:
            dropped[name] = f"{symbol(name)} is taken as given: {given[name]}"
        elif name not in family.depends:
            dropped[name] = not_measured(name, family.name)
        elif name in ("V", "delta") and "Fs" not in knowledge.ranges \
                and knowledge.values["Fs"] <= knowledge.values["Fc"]:
            dropped[name] = (f"{symbol(name)} describes a Stribeck drop that is not there "
                             "(Fs = Fc): no run determines it")
        elif name not in chosen:
            chosen.append(name)
    return chosen, dropped


def _outcome(knowledge: Knowledge, family, limits, runs, noise, targets, grid,
             quick=False) -> Outcome:
    setting_limits, notes = resolve_limits(knowledge, limits, family.limits)
    noise, noise_notes = _noise(knowledge, noise, family.name)
    notes = notes + noise_notes
    setting = Setting(setting_limits, noise, knowledge.F_hat, knowledge.z_ba, knowledge.units,
                      grid or (QUICK_GRID if quick else DEFAULT_GRID[family.name]))
    names, given = _parameters(knowledge, family)
    chosen, dropped = _targets(targets, knowledge, family, names, given)
    empty = Outcome(family, setting, names, chosen, None, None, None, None, None, None, None,
                    None, notes, dropped)
    if not chosen:
        return empty
    ranges = {name: knowledge.ranges[name] for name in names if name in knowledge.ranges}
    loose = {name: knowledge.values[name] for name in ranges
             if knowledge.stderr.get(name) is not None}
    draws = make_draws({n: knowledge.values[n] for n in PARAMETERS}, ranges, loose, coarse=quick)
    cands = family.candidates(draws.P, setting, draws.middle)
    empty.draws, empty.candidates = draws, cands
    if cands.size == 0:
        return empty
    info = family.information(cands, draws.P, setting, names, draws.middle)
    middle = draws.at(draws.middle)
    prior = weak_prior(names, middle, float(np.max(draws.P["Fs"])), setting.limits.v_max)
    now = existing_information(names, knowledge.values, knowledge.covariance) + prior
    now = np.broadcast_to(now, (draws.count, len(names), len(names))).copy()
    index = [names.index(name) for name in chosen]
    if info.rows is not None:
        runs = DEFAULT_RUNS[family.name] if runs is None else runs
        counts = choose_runs(now, info.rows, runs, index)
    else:
        if runs not in (None, 1):
            notes.append(f"The {family.name} is one record of {setting.limits.duration:g} s: "
                         f"runs = {runs} does not apply.")
        counts = choose_one(now, info.matrix, index)
    after = now + np.einsum("g,qgij->qij", counts, info.matrix)
    stderr, determined = verdicts(covariance(after), names, draws.P)
    return Outcome(family, setting, names, chosen, draws, cands, info, counts,
                   criterion(now, index), criterion(after, index), stderr, determined,
                   notes, dropped, now)


def _knowledge(report, params, ranges) -> Knowledge:
    if (report is None) == (params is None):
        raise PlanError("give either a report or params, not both and not neither",
                        ("report",) if report is not None else ("params",))
    if report is not None:
        return from_report(report, ranges)
    return from_params(params, ranges)


def plan_experiment(family: str, report: dict | None = None, params: dict | None = None,
                    limits: dict | None = None, runs: int | None = None,
                    noise: float | None = None, targets=None, ranges=None,
                    grid: int | None = None) -> dict:
    """The next experiment of ``family`` for a model (see the module docstring).

    Parameters
    ----------
    family : {'ramps', 'steady', 'sine'}
        Force ramps at chosen rates (break-away forces, E13), constant-speed set-points
        in both directions (E2), or one position sine through presliding and reversals
        (E6').
    report : dict, optional
        An identification report (``breakaway fit --json``): its final parameters,
        their covariance, what they leave open, its noise floor, units and extent.
    params : dict, optional
        Model parameters instead (``Fc``, ``Fs``, ``V``, ``delta``, ``sigma``, ``s``,
        ``z_ba``, ``F_hat``, ``m``), with nothing determined.
    limits : dict, optional
        ``u_max`` [N], ``v_max`` [m/s], ``v_min`` [m/s], ``travel`` [m], ``duration``
        [s] (of one run) and ``sample_rate`` [Hz]; defaults from the record.
    runs : int, optional
        Runs of the plan (ramps, set-points; the sine is one record).
    noise : float, optional
        Standard deviation of one measured force [N] (default: the record's floor).
    targets : list of str, optional
        Parameters to determine (default: those the data do not).
    ranges : dict, optional
        ``{name: [low, high]}``: take a parameter as open over this range.
    grid : int, optional
        Candidate design points.

    Returns
    -------
    dict
        ``family``, ``targets``, ``design``, ``predicted`` (per parameter: standard
        error now and after, determined now and after, and across an open range),
        ``programme`` (CSV text), ``notes``, ``limits``, ``noise``, ``units``,
        ``seconds``.

    Raises
    ------
    PlanError
        Naming the field of the request that is wrong.
    """
    started = time.perf_counter()
    if family not in FAMILIES:
        raise PlanError(f"family must be one of {', '.join(FAMILIES)}, got {family!r}",
                        ("family",))
    if runs is not None and (isinstance(runs, bool) or not isinstance(runs, int) or runs < 1):
        raise PlanError(f"runs must be a whole number >= 1, got {runs!r}", ("runs",))
    if grid is not None and (isinstance(grid, bool) or not isinstance(grid, int) or grid < 4):
        raise PlanError(f"grid must be a whole number >= 4, got {grid!r}", ("grid",))
    knowledge = _knowledge(report, params, ranges)
    try:
        outcome = _outcome(knowledge, FAMILIES[family], limits, runs, noise, targets, grid)
        result = describe(outcome, knowledge, lambda other, names: _would_determine(
            knowledge, other, limits, noise, names))
    except PlanError:
        raise
    except (np.linalg.LinAlgError, ArithmeticError, ValueError) as err:
        # magnitudes no rig has (a Stribeck velocity of 1e-30 beside forces of 1e30)
        # overflow the algebra: say so about the model given, never fail
        raise PlanError(f"the plan cannot be computed for these values ({err}); check the "
                        "model's magnitudes", ("report",) if report is not None else ("params",)
                        ) from err
    result = json_safe(result)
    result["seconds"] = round(time.perf_counter() - started, 4)
    return result


def _would_determine(knowledge, family: str, limits, noise, names) -> list[str]:
    """Which of ``names`` a quick plan of ``family`` determines over their open range."""
    try:
        outcome = _outcome(knowledge, FAMILIES[family], limits, None, noise, list(names),
                           None, quick=True)
    except PlanError:
        return []
    if outcome.determined_after is None:
        return []
    return [name for name in outcome.targets if outcome.determined_over_range(name)]


__all__ = ["FAMILIES", "Outcome", "plan_experiment"]
