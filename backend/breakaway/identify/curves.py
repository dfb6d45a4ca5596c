"""The rule for nested curves: a candidate that holds another as a special case (σ·|v|ⁿ
holds the line σ·|v| at n = 1) fits at least as well as it, and so keeps its extra
parameter only where the data ask for it — the exponent clearly not 1, the BIC and the
held-out error preferring the curve, in the round it comes in and again beside every
effect accepted after it; and a curve that no longer earns its place leaves its
straight form to be judged in its place.

:class:`NestedCurves` is the part of :class:`~.selection.Selection` that applies it."""

from __future__ import annotations

from .drop import level_on_bound
from .effects import EFFECTS
from .fitting import family, fit_model, weighted_rmse
from .indistinguishable import power_is_preferred
from .stability import unstable
from .straight import straight_forms
from .verdicts import Candidate, Step


class NestedCurves:
    """The nested-curve rule of a :class:`~.selection.Selection` (its data, judgement,
    verdicts and steps)."""

    def _extend_nested(self, current, trials):
        """A candidate that holds another as a special case (a curve with n = 1 is the
        straight line) fits at least as well as it: where its own starts fell short
        (a curve trapped in a basin five times worse than the line), it is fitted again
        from where the other ended."""
        for effect, trial in list(trials.items()):
            nested = EFFECTS[effect].extends
            if nested is None or nested[0] not in trials:
                continue
            inner = trials[nested[0]]
            if weighted_rmse(trial) <= weighted_rmse(inner):
                continue
            kin = family(current)
            try:
                again = fit_model(self.data, trial.effects, starts=[{**inner.params, **nested[1]}],
                                  screen=1, fixed=kin["fixed"], ties=kin["ties"])
            except (ValueError, FloatingPointError):
                continue
            if weighted_rmse(again) < weighted_rmse(trial):
                trials[effect] = again

    def _settle_power(self, passing, trials, current):
        """``viscous-power`` is named only when its n is clearly not 1 and the BIC and
        the held-out error prefer it; otherwise ``viscous``."""
        if "viscous-power" not in passing:
            return passing
        power, viscous = trials["viscous-power"], trials.get("viscous")
        self.verdicts["viscous-power"].heldout = self.heldout(power)
        straight = current  # the model the curve's straight form did not pass beside
        if viscous is not None and "viscous" in passing:
            self.verdicts["viscous"].heldout = self.heldout(viscous)
            straight = viscous
        preferred, why = power_is_preferred(power, viscous, self.weighted_heldout(power),
                                            self.weighted_heldout(straight))
        if preferred:
            if "viscous" in self.verdicts:
                self.verdicts["viscous"].reason = f"viscous-power describes the data better: {why}"
            return [e for e in passing if e != "viscous"]
        self.verdicts["viscous-power"].reason = f"named viscous, its straight form: {why}"
        return [e for e in passing if e != "viscous-power"]

    def straighten(self, current, current_heldout):
        """A curve in the model that holds another as a special case (σ·|v|ⁿ holds
        the line at n = 1) keeps its extra parameter only where it earns it beside every
        other effect of the model, as an effect does beside the model: a curve chosen
        in a round before the effects that came after (an inertia, an offset) can have
        bent towards what they explain."""
        for effect, line in straight_forms(self.data, current):
            if level_on_bound(line):
                # a line that takes a Coulomb level to its bound is no description of
                # the curve (a convex rise met by a line through the origin)
                continue
            line_heldout = self.heldout(line)
            beside = self.judgement.judge(line, current).reason
            why = f"its extra parameter does not earn its place beside the rest of the model: {beside}" \
                if beside else None
            if why is None and effect == "viscous-power":
                preferred, text = power_is_preferred(current, line,
                                                     self.weighted_heldout(current),
                                                     self.weighted_heldout(line))
                why = None if preferred else text
            if why is None:
                continue
            self._name_straight(effect, current, line, why, line_heldout)
            return self.straighten(line, line_heldout)
        return current, current_heldout

    def _straight_beside(self, current, effect, reduced):
        """``current`` with the curve ``effect`` in its straight form, where that line
        earns its place beside the rest of the model (``reduced``, the model without
        the curve) as an effect does in a forward round, else None. A curve that no
        longer earns its place leaves its special case to be judged: the line had been
        set aside because the curve described the data better, and the curve is now
        gone."""
        if EFFECTS[effect].extends is None:
            return None
        straight = EFFECTS[effect].extends[0]
        for curve, line in straight_forms(self.data, current):
            if curve == effect and not level_on_bound(line) and \
                    not EFFECTS[straight].unresolved(line.problem, line.params) and \
                    self.judgement.judge(reduced, line).reason is None and \
                    not unstable(self.data, line, straight):
                return line
        return None

    def _name_straight(self, effect, current, line, why, heldout):
        """Record that the model ``line`` names the curve ``effect`` of ``current`` in
        its straight form, for the reason ``why``."""
        straight = EFFECTS[effect].extends[0]
        self.verdicts[effect] = Candidate(current.rmse, current.bic, None, False,
                                          f"named {straight}, its special case: {why}")
        verdict = self.verdicts.setdefault(straight, Candidate())
        verdict.rmse, verdict.bic, verdict.accepted, verdict.reason = line.rmse, line.bic, True, None
        curve_step = next((s for s in reversed(self.steps) if s.effect == effect), None)
        evidence = f"{curve_step.evidence}; " if curve_step else ""
        self.steps.append(Step(straight, line, f"{evidence}named in its straight form, "
                               f"{straight}: {why}", heldout))

    def straightened_beside_drop(self, current, retried, heldout):
        """Record a curve of ``current`` (a model without a drop) that ``retried``, the
        same model with a Stribeck drop (:func:`~.drop.retried_drop`), names in its
        straight form: the curve's bend was the drop's."""
        for effect in current.effects:
            nested = EFFECTS[effect].extends
            if nested is None or effect in retried.effects or nested[0] not in retried.effects:
                continue
            self._name_straight(effect, current, retried, (
                f"with a Stribeck drop the line describes the data better (the BIC falls by "
                f"{current.bic - retried.bic:.1f} against the curve without one): the "
                f"curve's bend was the drop's"), heldout)


__all__ = ["NestedCurves"]
