"""The search for the effects the data hold: forward selection judged by
:mod:`.judgement` (the BIC, the held-out error block by block, an allowance for what the
library lacks) and the halves of a record (:mod:`.stability`), pairs when no single
effect passes (two missing effects can each hide the other's gain), then a backward
pass (drop an effect the others made redundant) and a swap pass (trade an accepted
effect for a close rival that explains the data better).

Between candidates that explain the data equally well (their BICs within
:data:`~.judgement.MIN_BIC_DROP`) the one with fewer parameters is named: an offset is
nested in an asymmetry up to the virgin branch, and a direction difference that one
constant describes needs no second level. A curve that holds a line as a special case
keeps its exponent only where the data ask for it (:mod:`.curves`)."""

from __future__ import annotations

import numpy as np

from .csvdata import Dataset
from .curves import NestedCurves
from .effects import EFFECTS
from .fitting import FitResult, best_base_starts, family, fit_model, fit_with_effect, refit
from .indistinguishable import (
    EXCLUSIVE,
    NESTED,
    beyond_nested,
    close_rivals,
    like_a_dependence,
    power_is_preferred,
    viscous_or_detection,
)
from .judgement import MIN_BIC_DROP, Judge
from .residuals import is_white
from .reweighing import Reweighing
from .stability import unstable
from .verdicts import Candidate, Step
from .warnings.beyond_data import beyond_data

#: Evaluations per parameter of a candidate's screening fit.
SCREEN_EVALUATIONS = 15
#: Candidates (by BIC) combined in pairs when no single effect passes.
PAIR_CANDIDATES = 3


class Selection(NestedCurves, Reweighing):
    """The state of one search: the data, the gates' verdicts, the steps taken."""

    def __init__(self, data: Dataset, noise: float, report, errors=None, velocity=None,
                 command=False):
        self.data = data
        #: each row's force error [N] that x's reading sets under the base model (what
        #: the data's weights, if any, were made of); None but for a time series of a
        #: measured force
        self.errors = errors
        #: the part of them that v's window sets under the model the weights were last
        #: taken from (:meth:`~.models.timeseries.TimeseriesProblem.velocity_errors`)
        self.velocity = velocity if velocity is not None or errors is None \
            else np.zeros_like(errors)
        self.noise = noise
        self.command = command
        self.report = report
        self.judgement = Judge(data, noise)
        self.restarts = best_base_starts(data)
        self.verdicts: dict[str, Candidate] = {}
        self.warnings: list[dict] = []
        self.steps: list[Step] = []
        self.settled: set[str] = set()  # named away by the rule for indistinguishable pairs
        #: effects that came within MIN_BIC_DROP of an accepted one in its round
        self.rivals: set[str] = set()
        #: simpler effects chosen over the richer ones nested in them ({simpler: richer})
        self.nested_choices: dict[str, str] = {}
        self.heldout_base = None
        #: per candidate, the dependence that would predict it as well (its verdict's twin)
        self.twins: dict[str, tuple | None] = {}
        #: whether the rows were weighed again under an accepted model (:meth:`reweigh`)
        self.reweighed = False
        #: a's error where it jumps, in the weights once a model reads a
        self.jumps = None

    def heldout(self, fit: FitResult) -> float:
        """The held-out error of ``fit``'s model [N] (:mod:`.heldout`)."""
        return self.judgement.heldout(fit).rmse

    def weighted_heldout(self, fit: FitResult) -> float:
        """The held-out error of ``fit``'s model [N] with the rows weighted as in its fit:
        what a model is judged by where x's reading makes some rows' forces uncertain
        (a turn inside one count of a coarse encoder, timed to a tenth of a second)."""
        return self.judgement.heldout(fit).weighted_rmse(fit.problem.data.weights)

    def white(self, fit: FitResult) -> bool:
        return is_white(fit.residual(), fit.problem, self.noise)

    def try_effect(self, current: FitResult, effect: str) -> FitResult | None:
        """A candidate's fit on a short budget: enough to rank the candidates and to
        reject the ones that do not help; the ones that pass are polished in full."""
        try:
            budget = SCREEN_EVALUATIONS * (len(current.problem.names) + len(EFFECTS[effect].keys) + 1)
            return fit_with_effect(self.data, current, effect, restarts=self.restarts,
                                   max_nfev=budget)
        except (ValueError, FloatingPointError) as exc:
            self.verdicts[effect] = Candidate(reason=f"the fit failed: {exc}")
            return None

    def forward(self, base: FitResult, available: list[str]) -> tuple[FitResult, float]:
        """Add effects one round at a time while the residual is not white."""
        current, current_heldout = base, self.heldout(base)
        if self.heldout_base is None:
            self.heldout_base = current_heldout
        remaining = [e for e in available if e not in base.effects
                     and e not in self.settled and EXCLUSIVE.get(e) not in base.effects]
        total = max(len(remaining), 1)
        while remaining and not self.white(current):
            trials = {}
            for i, effect in enumerate(remaining):
                refused = EFFECTS[effect].refuse(current.problem, current.residual())
                if refused:
                    self.verdicts[effect] = Candidate(reason=refused)
                    continue
                self.report(min(0.9, 0.1 + 0.8 * (len(self.steps) + i / total) / total),
                            f"trying {effect}")
                trial = self.try_effect(current, effect)
                if trial is not None:
                    trials[effect] = trial
            self._extend_nested(current, trials)
            chosen = self._choose(current, current_heldout, trials)
            if chosen is None:
                chosen = self._choose_pair(current, current_heldout, trials)
            if chosen is None:
                break
            for effect, fit, heldout, evidence in chosen:
                self.steps.append(Step(effect, fit, evidence, heldout))
                remaining.remove(effect)
                self._exclude_partner(effect, remaining)
                self.report(min(0.9, 0.1 + 0.8 * len(self.steps) / total), f"accepted {effect}")
            current, current_heldout = chosen[-1][1], chosen[-1][2]
            current, current_heldout = self.reweigh(current, current_heldout)
            current, current_heldout = self._revisit_nested(current, current_heldout,
                                                            available)
            # a richer form in place of the accepted one sets its own rows' errors
            current, current_heldout = self.reweigh(current, current_heldout)
            remaining = [e for e in remaining if e not in self.settled]
        if self.white(current):
            for effect in remaining:
                if effect not in self.settled:
                    verdict = self.verdicts.setdefault(effect, Candidate())
                    verdict.reason = "not needed: the residual is white without it"
        return current, current_heldout

    def _exclude_partner(self, effect, remaining):
        """The effect never in one model with ``effect`` (:data:`.indistinguishable.EXCLUSIVE`) is tried no more."""
        partner = EXCLUSIVE.get(effect)
        if partner in remaining:
            remaining.remove(partner)
            verdict = self.verdicts.setdefault(partner, Candidate())
            if verdict.reason is None:
                verdict.reason = f"never accepted together with {effect}, which was"

    def _evidence(self, effect, current, trial, note=""):
        text = EFFECTS[effect].signature(current.problem, current.residual(), trial.params)
        unit = self.data.unit("N")
        return (text + f"; with it the RMSE falls from {current.rmse:.4g} to {trial.rmse:.4g} {unit}"
                + f" and the BIC by {current.bic - trial.bic:.1f}" + note)

    def _choose(self, current, current_heldout, trials):
        passing = []
        for effect, trial in trials.items():
            verdict = self.judgement.judge(current, trial, heldout=False)
            if verdict.reason is None:
                trials[effect] = trial = refit(self.data, trial)  # the full polish
                verdict = self.judgement.judge(current, trial)
            reason = verdict.reason or EFFECTS[effect].unresolved(trial.problem, trial.params)
            held = self.heldout(trial) if verdict.heldout is not None else None
            self.verdicts[effect] = Candidate(trial.rmse, trial.bic, held, False, reason)
            self.twins[effect] = verdict.twin
            if reason is None:
                passing.append(effect)
        passing = self._settle_indistinguishable(passing, trials)
        passing = self._settle_power(passing, trials, current)
        for effect in self._parsimonious(by_parsimony(passing, trials), trials):
            trial = trials[effect]
            shaky = unstable(self.data, trial, effect)
            if shaky:
                self.verdicts[effect].reason = shaky
                continue
            self.rivals |= {e for e, t in trials.items()
                            if e != effect and t.bic <= trial.bic + MIN_BIC_DROP}
            # rivals: the other passing candidates not turned away on the way here
            rivals = [e for e in passing if e != effect and self.verdicts[e].reason is None]
            self.warnings += close_rivals(effect, trial, rivals, trials)
            if self.twins.get(effect):
                self.warnings.append(like_a_dependence(effect, trial, *self.twins[effect]))
            return [(effect, trial, self.heldout(trial), self._evidence(effect, current, trial))]
        return None

    def _parsimonious(self, ranked, trials) -> list[str]:
        """``ranked`` with the candidate to offer first: the first, unless one with
        fewer parameters passed too and the first shows nothing beyond it
        (:func:`~.indistinguishable.beyond_nested`: an asymmetry whose two directions'
        drops differ in nothing the data show) or does not pass the judgement against
        it (an asymmetry's second Stribeck level must earn its place beside an offset as
        any effect does beside the model: a lower BIC counted over every row, when the
        rows move together, is not that)."""
        if len(ranked) < 2:
            return ranked
        chosen = ranked[0]
        for other in ranked[1:]:
            if len(EFFECTS[other].keys) < len(EFFECTS[chosen].keys):
                if self._beyond_nested(chosen, other, trials[chosen]):
                    self.nested_choices[other] = chosen
                    chosen = other
                elif self.judgement.judge(trials[other], trials[chosen]).reason:
                    chosen = other
        return [chosen] + [e for e in ranked if e != chosen]

    def _revisit_nested(self, current, current_heldout, available):
        """An effect chosen over the richer one nested in it because that one showed
        nothing beyond it (:meth:`_parsimonious`: an offset over an asymmetry whose drops
        a fit without the viscous rise did not yet resolve) is judged again, by the
        swap's standard, each time the model beside it has grown. The swap after the
        forward rounds would come to the same, after a round of every other candidate
        beside a model that lacks the richer effect's part."""
        pending = {simpler: richer for simpler, richer in self.nested_choices.items()
                   if simpler in current.effects and len(current.effects) > 1}
        if not pending:
            return current, current_heldout
        return self.swap(current, current_heldout, available, only=pending)

    def _beyond_nested(self, richer, simpler, trial) -> str | None:
        """:func:`~.indistinguishable.beyond_nested`, with the parameters beyond what
        the data show as the report finds them."""
        if (richer, simpler) not in NESTED:
            return None
        return beyond_nested(richer, simpler, trial, beyond_data(trial, self.noise))

    def _settle_indistinguishable(self, passing, trials):
        # the pair predicts the same data: where one of them passes, the other's fit is
        # as good, whatever its own verdict (a σ that the drop's flat direction leaves
        # loose is still the other reading)
        pair = ("viscous", "detection")
        candidates = list(passing) + [e for e in pair if e in trials and e not in passing
                                      and any(q in passing for q in pair)]
        settled = viscous_or_detection(candidates, trials, "s" in self.data.meta)
        if settled is None:
            return passing
        named, other, entry = settled
        if named not in passing:
            return passing  # the rule's choice did not pass on its own
        self.warnings.append(entry)
        self.settled.add(other)
        self.verdicts[other].reason = (f"indistinguishable from {named} on these data; "
                                       f"named {named} by the rule for the two")
        return [e for e in passing if e != other]

    def _choose_pair(self, current, current_heldout, trials):
        """Two effects that pass together when neither does alone."""
        promising = sorted((e for e in trials if trials[e].bic < current.bic),
                           key=lambda e: trials[e].bic)[:PAIR_CANDIDATES]
        best = None
        for i, first in enumerate(promising):
            for second in promising[i + 1:]:
                if EXCLUSIVE.get(first) == second:  # never in one model
                    continue
                self.report(0.9, f"trying {first} with {second}")
                try:
                    pair = fit_with_effect(self.data, trials[first], second,
                                           restarts=self.restarts)
                except (ValueError, FloatingPointError):
                    continue
                if (best is None or pair.bic < best[2].bic) and not any(
                        EFFECTS[e].unresolved(pair.problem, pair.params) for e in (first, second)) \
                        and self.judgement.judge(current, pair).reason is None:
                    best = (first, second, pair)
        if best is None:
            return None
        first, second, pair = best
        # each earns its place beside the other, as an effect does beside the model (an
        # inertia refused alone as unstable does not carry a drift that adds 0.05 %)
        if any(self.judgement.judge(trials[one], pair).reason for one in (first, second)):
            return None
        if any(unstable(self.data, pair, e) for e in (first, second)):
            return None
        first_fit = trials[first]
        note = f"; accepted together with {second}, which it masked"
        return [(first, first_fit, self.heldout(first_fit),
                 self._evidence(first, current, first_fit, note)),
                (second, pair, self.heldout(pair), self._evidence(second, first_fit, pair))]

    def backward(self, current, current_heldout, keep_one=True):
        """Drop accepted effects that the others made redundant (parsimony), and those
        that no longer pass the verdict an effect must pass beside the rest of the model
        (an asymmetry accepted beside a straight viscous term, whose misfit differed by
        direction, is worth 0.1 % of the error beside the curve that replaced it); with
        ``keep_one=False`` also the last (an effect accepted beside a part of the model
        that was then taken out)."""
        changed = True
        while changed and len(current.effects) > (1 if keep_one else 0):
            changed = False
            for effect in current.effects:
                others = tuple(e for e in current.effects if e != effect)
                reduced = fit_model(self.data, others, starts=[current.params], screen=1,
                                    **family(current))
                kept = ", ".join(others) or "the model without a Stribeck drop"
                why = f"made redundant by {kept}" \
                    if reduced.bic <= current.bic + MIN_BIC_DROP / 2 else None
                if why is None and others:
                    beside = self.judgement.judge(reduced, current).reason
                    why = beside and f"no longer earns its place beside {kept}: {beside}"
                if why:
                    line = self._straight_beside(current, effect, reduced)
                    if line is not None:
                        current_heldout = self.heldout(line)
                        self._name_straight(effect, current, line, why, current_heldout)
                        current = line
                    else:
                        self.verdicts[effect] = Candidate(reduced.rmse, reduced.bic, None,
                                                          False, why)
                        current = reduced
                        current_heldout = self.heldout(reduced)
                    changed = True
                    break
        return current, current_heldout

    def swap(self, current, current_heldout, available, only=None):
        """Swap an accepted effect for a rival (a candidate that came close to an
        accepted one in its round) when the swap explains the data better: a forward
        step can take a stand-in for the true effect. ``only``: the one rival to try for
        each of some accepted effects ({accepted: rival}), in place of every pair."""
        rejected = [e for e in available if e not in current.effects and e in self.rivals
                    and e not in self.settled]
        for effect in list(current.effects):
            if only is not None and effect not in only:
                continue
            for candidate in rejected if only is None else [only[effect]]:
                others = tuple(e for e in current.effects if e != effect)
                if EXCLUSIVE.get(candidate) in others:
                    continue
                try:
                    reduced = fit_model(self.data, others, starts=[current.params], screen=1,
                                        **family(current))
                    trial = fit_with_effect(self.data, reduced, candidate, restarts=self.restarts)
                except (ValueError, FloatingPointError):
                    continue
                if trial.bic > current.bic - MIN_BIC_DROP or \
                        EFFECTS[candidate].unresolved(trial.problem, trial.params) or \
                        self.judgement.judge(reduced, trial).reason:
                    continue
                worse, _, held = self.judgement.compare(current, trial)
                heldout = held.rmse
                if worse or unstable(self.data, trial, candidate):
                    continue
                # a rival with more parameters must earn them against the model it
                # would replace, as in :meth:`_parsimonious`
                if len(EFFECTS[candidate].keys) > len(EFFECTS[effect].keys) and (
                        self._beyond_nested(candidate, effect, trial) or
                        self.judgement.judge(current, trial).reason):
                    continue
                if candidate == "viscous-power" and effect == "viscous" and not \
                        power_is_preferred(trial, current, self.weighted_heldout(trial),
                                           self.weighted_heldout(current))[0]:
                    continue
                self.verdicts[effect] = Candidate(reduced.rmse, reduced.bic, None, False,
                                                  f"replaced by {candidate}, which explains "
                                                  f"the data better")
                self.steps.append(Step(candidate, trial, self._evidence(
                    candidate, reduced, trial, f"; it replaces {effect}"), heldout))
                self.nested_choices.pop(effect, None)
                return (trial, heldout) if only is not None else \
                    self.swap(trial, heldout, available)
        return current, current_heldout


def by_parsimony(passing, trials) -> list[str]:
    """``passing`` in the order they are offered: the lowest BIC first, except that
    among the candidates within :data:`~.judgement.MIN_BIC_DROP` of it the one with
    fewer parameters comes first (they explain the data equally well)."""
    ranked = sorted(passing, key=lambda e: trials[e].bic)
    if not ranked:
        return ranked
    best = trials[ranked[0]].bic
    close = [e for e in ranked if trials[e].bic <= best + MIN_BIC_DROP]
    close.sort(key=lambda e: (len(EFFECTS[e].keys), trials[e].bic))
    return close + [e for e in ranked if e not in close]


__all__ = ["by_parsimony", "PAIR_CANDIDATES", "SCREEN_EVALUATIONS", "Selection"]
