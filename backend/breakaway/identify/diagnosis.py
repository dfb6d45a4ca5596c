"""The residual → effect loop (MODEL.md §7, §8).

1. Prepare the data (rows the model cannot use are dropped, with a warning), fit the
   base model, and estimate the noise floor without any model (:mod:`.noise`).
   Isolated spikes of the force are set aside and the base model fitted again
   (:mod:`.outliers`, with a warning); spikes that only the final model's residual
   shows (the base model's misfit hid them) send the data through once more.
2. While the residual is not white: fit every candidate effect that the data can show
   (all parameters refitted, starts read off the residual), and accept the lowest-BIC
   one that passes every gate — the BIC falls by at least :data:`MIN_BIC_DROP`, the fit
   removes a share :data:`MIN_EXCESS_EXPLAINED` of the residual variance above the noise
   floor, and the held-out error falls. When no single effect passes, pairs of the
   most promising candidates are tried together (two missing effects can each hide
   the other's gain). Effects that predict the same data are settled by MODEL.md §7's
   rule (``indistinguishable``).
3. Backward and swap passes: drop an accepted effect the others made redundant; swap
   one for a candidate that explains the data better (held-out error decides).
4. ``residual_white``, ``unexplained``, ``residual_structure`` and the warnings.

Long time series are screened on contiguous blocks spread over the record (each at the
full sampling rate, so reversals and velocities stay resolved); the base and final
models are then refitted on every row.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np
from threadpoolctl import threadpool_limits

from .csvdata import MIN_ROWS, Dataset
from .effects import (EFFECTS, MIN_RIPPLE_PERIODS, availability, long_wavelength,
                      viscous_equivalent_of_detection)
from .fitting import FitError, FitResult, best_base_starts, fit_model, fit_with_effect, refit
from .models import problem_for
from .noise import NoiseFloor, command_floor, estimate
from .outliers import SPIKE_SIGMAS, despiked_force, spike_rows
from .residuals import is_white, lag_one_correlation, residual_structure

#: A BIC drop of 10 is "very strong" evidence (Kass & Raftery 1995).
MIN_BIC_DROP = 10.0
#: An accepted effect removes at least this share of the residual variance above the
#: noise floor (an effect that is there removes nearly all of its own part).
MIN_EXCESS_EXPLAINED = 0.25
#: ... and at least this relative share of the RMSE.
MIN_RMSE_GAIN = 0.01
#: Structure is "clear" when the final RMSE exceeds the noise floor by this factor.
UNEXPLAINED_RATIO = 1.3
#: ... unless the residual is noise-like: successive residuals correlate less than this,
#: and no variable explains more than :data:`NOISE_LIKE_SHARE` of it (noise whose
#: spread changes: the floor, a median of differences, reads below its RMS).
NOISE_LIKE_CORRELATION = 0.1
NOISE_LIKE_SHARE = 0.05
#: Noise is uneven when its RMS in one bin of the rows by some variable (up to ten, of
#: 50 rows or more) is this many times that in another.
UNEVEN_SPREAD = 1.5
#: Time series longer than this are screened on a decimated copy of about this size.
SCREEN_ROWS = 20_000
#: Function evaluations (each with a finite-difference Jacobian) of a refit on every row
#: from the screened solution: it only polishes.
FULL_REFIT_EVALUATIONS = 8
#: ... in this many contiguous blocks.
SCREEN_BLOCKS = 8
#: Evaluations per parameter of a candidate's screening fit.
SCREEN_EVALUATIONS = 15
#: Candidates (by BIC) combined in pairs when no single effect passes.
PAIR_CANDIDATES = 3


@dataclass
class Step:
    effect: str
    fit: FitResult
    evidence: str
    heldout: float


@dataclass
class Candidate:
    """The last verdict on one library effect."""

    rmse: float | None = None
    bic: float | None = None
    heldout: float | None = None
    accepted: bool = False
    reason: str | None = None


@dataclass
class Diagnosis:
    """Everything the report and the explorer's data panel show."""

    data: Dataset
    noise: NoiseFloor
    base: FitResult
    final: FitResult
    steps: list[Step]
    heldout_before: float
    heldout_after: float
    white: bool
    unexplained: bool
    candidates: dict[str, Candidate] = field(default_factory=dict)
    warnings: list[dict] = field(default_factory=list)
    structure: list[dict] = field(default_factory=list)
    screened_rows: int = 0
    seconds: float = 0.0

    @property
    def effects(self) -> list[str]:
        return list(self.final.effects)


def warning(code: str, parameter: str | None, message: str) -> dict:
    """One entry of the report's ``warnings`` (MODEL.md §8)."""
    return {"code": code, "parameter": parameter, "message": message}


# ---------------------------------------------------------------------------------
# data preparation
# ---------------------------------------------------------------------------------


def subset(data: Dataset, rows, segments=()) -> Dataset:
    """The same dataset restricted to ``rows`` (indices, in order)."""
    rows = np.asarray(rows)
    return Dataset(kind=data.kind, columns={k: v[rows] for k, v in data.columns.items()},
                   meta=data.meta, n=int(rows.size), ignored_columns=data.ignored_columns,
                   lines=data.lines[rows], meta_lines=data.meta_lines,
                   segments=tuple(segments))


def screening_blocks(data: Dataset, directions=None, rows: int = None,
                     count: int = None) -> Dataset:
    """:data:`SCREEN_BLOCKS` contiguous blocks spread evenly over a long time series,
    :data:`SCREEN_ROWS` rows in all, as independent records: each keeps the full
    sampling (reversals, presliding and velocity stay resolved) and together they
    span the whole duration (a drift stays visible). Given the record's
    ``directions``, each block starts at a motion reversal, where (E6')'s state is
    known: x_r and F_r are the block's first position and measured force."""
    rows = rows or SCREEN_ROWS
    count = count or SCREEN_BLOCKS
    length = rows // count
    starts = np.linspace(0, data.n - length, count).astype(int)
    if directions is not None:
        turns = np.flatnonzero(np.diff(directions) != 0)  # the sample before a reversal
        turns = turns[turns <= data.n - length]
        if turns.size:
            at = np.searchsorted(turns, starts[1:])
            starts[1:] = turns[np.minimum(at, turns.size - 1)]
            starts = np.unique(starts)
            # blocks may not overlap: keep the ones that fit after their predecessor
            kept = [starts[0]]
            for a in starts[1:]:
                if a >= kept[-1] + length:
                    kept.append(a)
            starts = np.array(kept)
    index = np.concatenate([np.arange(a, a + length) for a in starts])
    return subset(data, index, segments=[i * length for i in range(1, starts.size)])


def prepare(data: Dataset) -> tuple[Dataset, list[dict]]:
    """Drop the rows the model cannot use: steady rows at v = 0 (E2 has no force there,
    the measured one is whatever stiction held)."""
    if data.kind != "steady":
        return data, []
    at_rest = data.columns["v"] == 0
    count = int(np.count_nonzero(at_rest))
    if not count:
        return data, []
    kept = np.flatnonzero(~at_rest)
    if kept.size < MIN_ROWS:
        raise FitError(f"only {kept.size} rows have v ≠ 0; at least {MIN_ROWS} are needed")
    lines = ", ".join(str(int(x)) for x in data.lines[at_rest][:5])
    more = ", …" if count > 5 else ""
    return subset(data, kept), [warning(
        "dropped-rows", None,
        f"{count} of {data.n} rows have v = 0 (lines {lines}{more}); steady friction is not "
        "defined at rest, so they were left out")]


def heldout_rows(data: Dataset):
    """Training rows and held-out rows (§8: the last 20 % of a timeseries, every 5th
    row otherwise)."""
    n = data.n
    idx = np.arange(n)
    if data.kind == "timeseries":
        cut = int(round(0.8 * n))
        return idx[:cut], idx[cut:]
    test = idx[4::5]
    return np.setdiff1d(idx, test), test


#: Evaluations of the refit on the training rows (it starts at the fit on every row).
HELDOUT_EVALUATIONS = 20


def _heldout_error(data: Dataset, fit: FitResult, train, test) -> float:
    trained = refit(data, fit, rows=train, max_nfev=HELDOUT_EVALUATIONS)
    r = trained.problem.measured[test] - trained.prediction[test]
    return math.sqrt(float(np.mean(r**2)))


# ---------------------------------------------------------------------------------
# the gates
# ---------------------------------------------------------------------------------


def _gate(current: FitResult, trial: FitResult, noise: float, added: int = 1) -> str | None:
    """Why ``trial`` does not improve on ``current`` enough (None: it passes)."""
    drop = current.bic - trial.bic
    if not drop >= MIN_BIC_DROP * added:
        return f"the BIC falls by {drop:.1f}, less than the {MIN_BIC_DROP * added:g} required"
    if trial.rmse > (1 - MIN_RMSE_GAIN) * current.rmse:
        gain = 100 * (1 - trial.rmse / current.rmse)
        return f"the RMSE falls by only {gain:.2g} %"
    excess = current.rmse**2 - noise**2
    if excess <= 0:
        return "the residual is already at the noise floor"
    share = (current.rmse**2 - trial.rmse**2) / excess
    if share < MIN_EXCESS_EXPLAINED * added:
        return (f"it explains {100 * share:.0f} % of the residual variance above the noise "
                f"floor, less than the {100 * MIN_EXCESS_EXPLAINED * added:.0f} % required")
    return None


class _Loop:
    """The state of one diagnosis: the screened data, the gates' verdicts, the steps."""

    def __init__(self, data: Dataset, noise: float, report):
        self.data = data
        self.noise = noise
        self.report = report
        self.train, self.test = heldout_rows(data)
        self.restarts = best_base_starts(data)
        self.verdicts: dict[str, Candidate] = {}
        self.warnings: list[dict] = []
        self.steps: list[Step] = []
        self.settled: set[str] = set()  # named away by MODEL.md §7's rule
        #: effects that came within MIN_BIC_DROP of an accepted one in its round
        self.rivals: set[str] = set()

    def heldout(self, fit: FitResult) -> float:
        return _heldout_error(self.data, fit, self.train, self.test)

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

    def run(self, base: FitResult, available: list[str]) -> tuple[FitResult, float]:
        current, current_heldout = base, self.heldout(base)
        self.heldout_base = current_heldout
        remaining = list(available)
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
            chosen = self._choose(current, current_heldout, trials)
            if chosen is None:
                chosen = self._choose_pair(current, current_heldout, trials)
            if chosen is None:
                break
            for effect, fit, heldout, evidence in chosen:
                self.steps.append(Step(effect, fit, evidence, heldout))
                remaining.remove(effect)
                self.report(min(0.9, 0.1 + 0.8 * len(self.steps) / total), f"accepted {effect}")
            current, current_heldout = chosen[-1][1], chosen[-1][2]
            remaining = [e for e in remaining if e not in self.settled]
        if self.white(current):
            for effect in remaining:
                if effect not in self.settled:
                    verdict = self.verdicts.setdefault(effect, Candidate())
                    verdict.reason = "not needed: the residual is white without it"
        return current, current_heldout

    def _evidence(self, effect, current, trial, note=""):
        text = EFFECTS[effect].signature(current.problem, current.residual(), trial.params)
        return (text + f"; with it the RMSE falls from {current.rmse:.4g} to {trial.rmse:.4g} N"
                + f" and the BIC by {current.bic - trial.bic:.1f}" + note)

    def _choose(self, current, current_heldout, trials):
        passing = []
        for effect, trial in trials.items():
            reason = _gate(current, trial, self.noise)
            if reason is None:
                trials[effect] = trial = refit(self.data, trial)  # the full polish
            self.verdicts[effect] = Candidate(trial.rmse, trial.bic, None, False, reason)
            if reason is None:
                passing.append(effect)
        passing = self._settle_indistinguishable(passing, trials)
        for effect in sorted(passing, key=lambda e: trials[e].bic):
            trial = trials[effect]
            heldout = self.heldout(trial)
            self.verdicts[effect].heldout = heldout
            if heldout < current_heldout:
                self.rivals |= {e for e, t in trials.items()
                                if e != effect and t.bic <= trial.bic + MIN_BIC_DROP}
                self._warn_close(effect, trial, [e for e in passing if e != effect], trials)
                return [(effect, trial, heldout, self._evidence(effect, current, trial))]
            self.verdicts[effect].reason = (f"the held-out error rises from "
                                            f"{current_heldout:.4g} to {heldout:.4g} N")
        return None

    def _warn_close(self, effect, trial, others, trials):
        """``indistinguishable`` when another passing candidate explains the data almost as
        well (its BIC within MIN_BIC_DROP): the data do not decide between the two."""
        for other in others:
            gap = trials[other].bic - trial.bic
            if gap > MIN_BIC_DROP:
                continue
            values = ", ".join(f"{k} = {trials[other].params[k]:.4g}" for k in EFFECTS[other].keys)
            self.warnings.append(warning("indistinguishable", other, (
                f"{other} explains these data almost as well as {effect} (its BIC is only "
                f"{gap:.1f} higher; {MIN_BIC_DROP:g} would decide): {effect} is named for "
                f"the lower BIC, the other reading is {other} with {values}")))

    def _settle_indistinguishable(self, passing, trials):
        """MODEL.md §7: on break-away data viscous and detection raise F_ba alike where F̂
        does not vary; name one by the rule and give the other's value."""
        if not {"viscous", "detection"} <= set(passing):
            return passing
        v, d = trials["viscous"], trials["detection"]
        if abs(v.bic - d.bic) >= MIN_BIC_DROP:
            return passing
        problem = v.problem
        has_s = "s" in self.data.meta
        named, other = ("viscous", "detection") if has_s else ("detection", "viscous")
        F_hat = problem.F_hat(v.params["Fc"], v.params["Fs"])
        if has_s:
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
        self.warnings.append(warning("indistinguishable", other, text))
        self.settled.add(other)
        self.verdicts[other].reason = (f"indistinguishable from {named} on these data; "
                                       f"named {named} by the rule of MODEL.md §7")
        return [e for e in passing if e != other]

    def _choose_pair(self, current, current_heldout, trials):
        """Two effects that pass the gates together when neither does alone."""
        promising = sorted((e for e in trials if trials[e].bic < current.bic),
                           key=lambda e: trials[e].bic)[:PAIR_CANDIDATES]
        best = None
        for i, first in enumerate(promising):
            for second in promising[i + 1:]:
                self.report(0.9, f"trying {first} with {second}")
                try:
                    pair = fit_with_effect(self.data, trials[first], second,
                                           restarts=self.restarts)
                except (ValueError, FloatingPointError):
                    continue
                if _gate(current, pair, self.noise, added=2) is None and (
                        best is None or pair.bic < best[2].bic):
                    best = (first, second, pair)
        if best is None:
            return None
        first, second, pair = best
        heldout = self.heldout(pair)
        if heldout >= current_heldout:
            return None
        first_fit = trials[first]
        note = f"; accepted together with {second}, which it masked"
        return [(first, first_fit, self.heldout(first_fit),
                 self._evidence(first, current, first_fit, note)),
                (second, pair, heldout, self._evidence(second, first_fit, pair))]

    def backward(self, current, current_heldout):
        """Drop accepted effects that the others made redundant (parsimony)."""
        changed = True
        while changed and len(current.effects) > 1:
            changed = False
            for effect in current.effects:
                others = tuple(e for e in current.effects if e != effect)
                reduced = fit_model(self.data, others, starts=[current.params], screen=1)
                if reduced.bic <= current.bic + MIN_BIC_DROP / 2:
                    kept = ", ".join(others)
                    self.verdicts[effect] = Candidate(reduced.rmse, reduced.bic, None, False,
                                                      f"made redundant by {kept}")
                    current = reduced
                    current_heldout = self.heldout(reduced)
                    changed = True
                    break
        return current, current_heldout

    def swap(self, current, current_heldout, available):
        """Swap an accepted effect for a rival (a candidate that came close to an
        accepted one in its round) when the swap explains the data better: a forward
        step can take a stand-in for the true effect."""
        rejected = [e for e in available if e not in current.effects and e in self.rivals
                    and e not in self.settled]
        for effect in list(current.effects):
            for candidate in rejected:
                others = tuple(e for e in current.effects if e != effect)
                try:
                    reduced = fit_model(self.data, others, starts=[current.params], screen=1)
                    trial = fit_with_effect(self.data, reduced, candidate, restarts=self.restarts)
                except (ValueError, FloatingPointError):
                    continue
                if trial.bic > current.bic - MIN_BIC_DROP:
                    continue
                heldout = self.heldout(trial)
                if heldout >= current_heldout:
                    continue
                self.verdicts[effect] = Candidate(reduced.rmse, reduced.bic, None, False,
                                                  f"replaced by {candidate}, which explains "
                                                  f"the data better")
                self.steps.append(Step(candidate, trial, self._evidence(
                    candidate, reduced, trial, f"; it replaces {effect}"), heldout))
                return self.swap(trial, heldout, available)
        return current, current_heldout


def diagnose(data: Dataset, progress=None) -> Diagnosis:
    """Fit, trace the residual to missing effects, and refit (see module docstring).

    Parameters
    ----------
    data : Dataset
    progress : callable, optional
        Called as ``progress(fraction, message)`` as the work advances; an exception it
        raises ends the diagnosis (how a job is cancelled).
    """
    # one BLAS thread: the Jacobians are tall and thin, threads only contend
    with threadpool_limits(limits=1, user_api="blas"):
        return _diagnose(data, progress)


@dataclass
class SetAside:
    """The spikes set aside so far (:mod:`.outliers`), for the report's warning."""

    rows: int  # rows of the data before any was set aside
    base_rmse: float  # the base model's RMSE with the spikes in [N]
    lines: list = field(default_factory=list)
    spreads: list = field(default_factory=list)

    def add(self, data: Dataset, spikes, scale) -> None:
        self.lines.extend(int(line) for line in data.lines[spikes])
        self.spreads.extend(float(value) for value in scale[spikes])

    def warning(self, kind: str) -> dict:
        count = len(self.lines)
        lines = ", ".join(str(line) for line in sorted(self.lines)[:5])
        more = ", …" if count > 5 else ""
        done = ("their F was replaced by the median of their neighbours'"
                if kind == "timeseries" else "they were left out")
        return warning("outliers", "F_ba" if kind == "breakaway" else "F", (
            f"{count} of {self.rows} rows (lines {lines}{more}) are isolated spikes, more "
            f"than {SPIKE_SIGMAS:g} times the residual's local spread "
            f"({float(np.median(self.spreads)):.3g} N) from their neighbours: glitches of "
            f"the measurement, not friction; {done}, and the base model's RMSE with them "
            f"was {self.base_rmse:.4g} N"))


def _diagnose(data: Dataset, progress, set_aside: SetAside | None = None,
              carried: list | None = None) -> Diagnosis:
    """One pass; a second (given ``set_aside`` and the first pass's data warnings,
    ``carried``) when the final residual shows spikes that the base one did not."""
    started = time.perf_counter()
    report = progress or (lambda fraction, message: None)
    report(0.0, "fitting the base model")
    data, prepared = prepare(data)
    prepared = [*(carried or []), *prepared]
    screened = data.kind == "timeseries" and data.n > 1.5 * SCREEN_ROWS
    full_problem, screen, screen_base, base = _base_fits(data, screened)
    noise = estimate(full_problem)
    spikes, scale = spike_rows(base.problem, base.residual(), noise.value)
    if spikes.any():
        set_aside = set_aside or SetAside(data.n, base.rmse)
        set_aside.add(data, spikes, scale)
        data = without_spikes(data, spikes)
        full_problem, screen, screen_base, base = _base_fits(data, screened, screen_base)
        noise = estimate(full_problem)
    warnings = list(prepared)
    command = command_floor(full_problem, noise, base.residual())
    from_x = base.problem.resolution_noise(base.params) if data.kind == "timeseries" else 0.0
    if command is not None:
        # the residual is the noise of x seen through the model; its differences
        # under-read it where the model smooths x (v over a window)
        noise = command.at_least_position_part(from_x)
    elif data.kind == "timeseries":
        noise = noise.with_position_part(from_x)
    warnings += _data_warnings(full_problem, noise)
    report(0.1, "screening candidate effects")

    loop = _Loop(screen, noise.value, report)
    available = []
    for effect, why in availability(screen_base.problem).items():
        if why is None:
            available.append(effect)
        else:
            loop.verdicts[effect] = Candidate(reason=why)
    current, current_heldout = loop.run(screen_base, available)
    heldout_before = loop.heldout_base
    if len(current.effects) > 1:
        current, current_heldout = loop.backward(current, current_heldout)
    if current.effects and not loop.white(current):
        # a swap only pays where structure is left: with a white residual no rival can
        # lower the BIC by MIN_BIC_DROP
        current, current_heldout = loop.swap(current, current_heldout, available)
    steps = [s for s in loop.steps if s.effect in current.effects]
    if screened:
        report(0.92, "refitting the chosen model on every row")
        final = refit(data, current, max_nfev=FULL_REFIT_EVALUATIONS) \
            if current.effects else base
        steps = [Step(s.effect, final if s.fit is current else _evaluate(data, s.fit),
                      s.evidence, s.heldout) for s in steps]
    else:
        final = current
    if carried is None and final.effects:
        late, scale = spike_rows(final.problem, final.residual(), noise.value)
        if late.any():
            set_aside = set_aside or SetAside(data.n, base.rmse)
            set_aside.add(data, late, scale)
            return _diagnose(without_spikes(data, late), progress, set_aside,
                             carried=prepared)
    for name in final.effects:
        loop.verdicts[name] = Candidate(final.rmse, final.bic, current_heldout, True, None)
    white = is_white(final.residual(), final.problem, noise.value)
    structure = residual_structure(final.residual(), final.problem, white)
    floor_low = [] if white else _floor_low_warnings(final, noise.value, structure)
    unexplained = (not white) and final.rmse > UNEXPLAINED_RATIO * noise.value \
        and not floor_low
    warnings += loop.warnings + _fit_warnings(final) + _travel_warnings(final, structure) \
        + floor_low
    if set_aside is not None:
        warnings.insert(len(prepared), set_aside.warning(data.kind))
    report(1.0, "done")
    return Diagnosis(data, noise, base, final, steps, heldout_before, current_heldout,
                     white, unexplained, loop.verdicts, warnings, structure,
                     screen.n if screened else 0, time.perf_counter() - started)


def _base_fits(data: Dataset, screened: bool, start: FitResult | None = None):
    """The problem on every row, the rows screened, and the base fits on both (from
    ``start``'s parameters when given)."""
    full_problem = problem_for(data)
    screen = screening_blocks(data, full_problem.d) if screened else data
    screen_base = base = fit_model(screen, starts=None if start is None else [start.params])
    if screened:
        base = refit(data, screen_base, max_nfev=FULL_REFIT_EVALUATIONS)
    return full_problem, screen, screen_base, base


def without_spikes(data: Dataset, spikes) -> Dataset:
    """``data`` with its spikes set aside: a time series keeps every row (its presliding
    state runs along x) with each spike's F replaced by the median of its neighbours';
    the other kinds' rows are separate measurements, and a spike's row is left out."""
    if data.kind != "timeseries":
        return subset(data, np.flatnonzero(~spikes))
    return replace(data, columns={**data.columns,
                                  "F": despiked_force(data.columns["F"], spikes)})


def _evaluate(data, fit):
    """``fit``'s parameters evaluated on ``data`` without moving them."""
    return fit_model(data, fit.effects, starts=[fit.params], screen=1, max_nfev=1)


# ---------------------------------------------------------------------------------
# warnings
# ---------------------------------------------------------------------------------


def _data_warnings(problem, noise: NoiseFloor) -> list[dict]:
    out = []
    q_x = getattr(problem, "quantum_x", 0.0)
    if q_x > 0:
        part = (f"; through the model they add {noise.from_x:.3g} N to the noise floor"
                if noise.from_x > 0 else "")
        out.append(warning("quantised", "x", (
            f"x takes steps of {q_x:.4g}: direction changes of up to {problem.hysteresis:.4g} "
            f"(3 steps) are not reversals, and v is taken over a window of several "
            f"samples{part}")))
    if noise.quantum_F > 0:
        floor = noise.quantum_F / math.sqrt(12)
        column = "F_ba" if problem.kind == "breakaway" else "F"
        out.append(warning("quantised", column, (
            f"{column} takes steps of {noise.quantum_F:.4g} N: the noise floor is not taken "
            f"below q/√12 = {floor:.4g} N")))
    if noise.command:
        out.append(warning("force-is-command", "F", (
            f"the force column is noise-free (differences estimate {noise.smooth_F:.3g} N): "
            f"it is a command and the measurement noise sits in x (std about "
            f"{getattr(problem, 'noise_x', 0.0):.3g}); the noise floor {noise.value:.4g} N is "
            f"the larger of the base model's residual differences and that noise of x run "
            f"through the model ({noise.from_x:.3g} N)")))
    counts = problem.direction_counts()
    if counts is not None and problem.kind != "breakaway":
        pos, neg, total = counts
        reason = EFFECTS["asymmetry"].unavailable(problem)
        if reason and reason.startswith("one-direction"):
            share = 100 * min(pos, neg) / max(total, 1)
            out.append(warning("one-direction", None, (
                f"motion is essentially in one direction ({pos} rows positive, {neg} negative, "
                f"{share:.2g} % the other way): offset and asymmetry are not tried, since "
                f"an offset and the level cannot be separated without both directions")))
    if problem.kind == "breakaway" and problem.level_only:
        rates = ", ".join(f"{k:g}" for k in np.unique(problem.k))
        out.append(warning("single-rate", None, (
            f"break-away measured at {problem.distinct_rates} distinct rate(s) (k = {rates}): "
            f"only the level is determined; it is reported as Fs (= Fc), and V and δ are "
            f"not determined")))
    return out


_WHY = {
    "flat": "moves along a flat direction of the fit",
    "relative": "has a standard error larger than its value",
    "artefact": "has a standard error below 1e-9 of its value (a numerical artefact)",
}


def _fit_warnings(fit: FitResult) -> list[dict]:
    out = []
    a = fit.assessment
    for name, reason in a.why.items():
        if reason is None or reason == "fixed":
            continue
        value = fit.params[name]
        if reason == "at-bound":
            side = a.bound.get(name, "a")
            text = f"{name} = {value:.4g} ended on the {side} bound of its range"
            if name in ("Fs", "Fs_neg"):
                low = "Fc" if name == "Fs" else "Fc_neg"
                text += (f" ({name} = {low}): the data show no velocity weakening, so the "
                         f"Stribeck velocity and shape are not determined")
            out.append(warning("at-bound", name, text + "; it is not a result"))
            continue
        if reason.startswith("correlated:"):
            other = reason.split(":", 1)[1]
            text = (f"{name} = {value:.4g} is correlated above 0.99 with {other}: the data "
                    f"determine a combination of the two, not each")
        else:
            se = a.stderr.get(name)
            se_text = f" (± {se:.2g})" if se is not None else ""
            text = f"{name} = {value:.4g}{se_text} {_WHY[reason]}: the data do not determine it"
        out.append(warning("undetermined", name, text))
    return out


def _floor_low_warnings(fit: FitResult, floor: float, structure: list[dict]) -> list[dict]:
    """``floor-low`` when the residual exceeds the floor as far as structure would
    (:data:`UNEXPLAINED_RATIO`) but is noise-like (:data:`NOISE_LIKE_CORRELATION`): the
    floor reads low, nothing is missing."""
    if not fit.rmse > UNEXPLAINED_RATIO * floor:
        return []
    residual = fit.residual()
    correlation = lag_one_correlation(residual, fit.problem)
    strongest = max((item["strength"] for item in structure), default=0.0)
    if abs(correlation) >= NOISE_LIKE_CORRELATION or strongest >= NOISE_LIKE_SHARE:
        return []
    along, ratio = max(((name, _spread_ratio(residual, values))
                        for name, values in fit.problem.variables().items()),
                       key=lambda item: item[1], default=(None, 1.0))
    why = (f"its spread changes {ratio:.1f}-fold along {along}, and the floor (a median) "
           "reads the quiet part" if ratio >= UNEVEN_SPREAD
           else "its spread is even, so the floor itself reads low (a median of "
           "differences, or a quantisation's q/√12, misses part of the noise)")
    return [warning("floor-low", None, (
        f"the residual is noise-like (successive values correlate {correlation:+.2f}, no "
        f"variable explains {100 * NOISE_LIKE_SHARE:.0f} % of it) but its RMS, "
        f"{fit.rmse:.3g}, is {fit.rmse / floor:.2f} times the noise floor: {why}; no "
        "effect is missing"))]


def _spread_ratio(residual, values) -> float:
    """Largest over smallest RMS of the residual in up to 10 equal-count bins of
    ``values``, of 50 rows or more (fewer rows would read chance as unevenness)."""
    bins = int(np.clip(residual.size // 50, 1, 10))
    order = np.argsort(values, kind="stable")
    rms = [math.sqrt(float(np.mean(part**2))) for part in np.array_split(residual[order], bins)
           if part.size]
    return max(rms) / min(rms) if min(rms) > 0 else math.inf


def _travel_warnings(fit: FitResult, structure: list[dict]) -> list[dict]:
    """``short-travel``: the residual depends on x at a scale the travel cannot hold
    twice, so ``ripple`` was not tried there."""
    if fit.problem.kind != "timeseries" or not structure or "ripple" in fit.effects:
        return []
    strength = {s["against"]: s["strength"] for s in structure}.get("x", 0.0)
    lam = long_wavelength(fit.problem, fit.residual())
    if strength < 0.1 or lam is None:
        return []
    travel = fit.problem.scales.travel
    return [warning("short-travel", None, (
        f"the residual depends on x ({100 * strength:.0f} % of its variance), most strongly "
        f"at a wavelength of about {lam:.3g} over a travel of {travel:.3g}: the travel holds "
        f"fewer than {MIN_RIPPLE_PERIODS:g} such periods, so ripple is not tried there"))]


__all__ = ["Candidate", "Diagnosis", "MIN_BIC_DROP", "Step", "diagnose", "heldout_rows",
           "prepare", "subset", "warning"]
