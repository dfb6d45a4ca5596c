"""The residual → effect loop.

1. Prepare the data (rows the model cannot use are dropped, :mod:`.preparation`), fit
   the base model, and estimate the noise floor without any model (:mod:`.noise`).
   Isolated spikes of the force are set aside and the base model fitted again
   (:mod:`.outliers`, with a warning); spikes that only the final model's residual
   shows (the base model's misfit hid them) send the data through once more.
2. Search for the effects the data hold (:mod:`.selection`, judged by
   :mod:`.judgement`: the BIC, the held-out error on blocks of :mod:`.heldout`, an
   allowance for what the library lacks from :mod:`.allowance`); effects that predict
   the same data are settled by the rule of :mod:`.indistinguishable`.
3. A Stribeck drop the data do not resolve is taken out (:mod:`.drop`): Fc comes from
   the model without it.
4. The share of the error that x's resolution sets (``input_floor``),
   ``residual_white``, ``unexplained``, ``residual_structure`` and the warnings, one
   module per rule (:mod:`.warnings`).

Long time series are screened on blocks (:mod:`.screening`); the base and final models
are then refitted on every row.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np
from threadpoolctl import threadpool_limits

from .csvdata import Dataset
from .effects import availability
from .fitting import FitResult, fit_model, refit
from .models import problem_for, with_weights
from .drop import drop_bound_text, retried_drop, unresolved_drop, without_drop
from .input_error import input_floor, input_weights, misfit_ratio, scaled_residual
from .noise import NoiseFloor, estimate, is_command, programmed_force
from .outliers import spike_rows
from .preparation import SetAside, prepare, without_spikes
from .profile import confirm_correlated, follows_no_variable
from .residuals import is_white, residual_structure
from .screening import FULL_REFIT_EVALUATIONS, needs_screening, screening_blocks
from .selection import Selection
from .verdicts import Candidate, Step
from .warnings.beyond_data import beyond_data, beyond_data_warnings, mark_beyond
from .warnings.data import data_warnings
from .warnings.fit import fit_warnings
from .warnings.floor_low import UNEXPLAINED_RATIO, floor_low_warnings
from .warnings.stick_slip import stick_slip_warnings
from .warnings.travel import travel_warnings


#: Spikes in a screened (long) record send the base model through its fits again only
#: when they are more than this share of the rows.
REFIT_SPIKE_SHARE = 1e-4


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
    input_floor: float
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


def _search(search: Selection, start: FitResult, available):
    """Forward rounds from ``start``, a backward pass, and a swap where structure is left
    (with a white residual no rival can lower the BIC by the required drop); after a
    swap, the effect it took out may still be there beside its replacement."""
    current, current_heldout = search.forward(start, available)
    if len(current.effects) > 1:
        current, current_heldout = search.backward(current, current_heldout)
    if current.effects and not search.white(current):
        swapped, swapped_heldout = search.swap(current, current_heldout, available)
        if swapped is not current:
            current, current_heldout = search.forward(swapped, available)
            if len(current.effects) > 1:
                current, current_heldout = search.backward(current, current_heldout)
    return search.straighten(current, current_heldout)


def _diagnose(data: Dataset, progress, set_aside: SetAside | None = None,
              carried: list | None = None) -> Diagnosis:
    """One pass; a second (given ``set_aside`` and the first pass's data warnings,
    ``carried``) when the final residual shows spikes that the base one did not."""
    started = time.perf_counter()
    report = progress or (lambda fraction, message: None)
    report(0.0, "fitting the base model")
    data, prepared = prepare(data)
    prepared = [*(carried or []), *prepared]
    screened = needs_screening(data)
    full_problem, screen, screen_base, base = _base_fits(data, screened)
    noise = estimate(full_problem)
    commanded = programmed_force(full_problem, noise)
    # a commanded force has no glitches: its sharp changes were commanded
    spikes, scale = spike_rows(base.problem, base.residual(), noise.value)
    if spikes.any() and not commanded:
        set_aside = set_aside or SetAside(data.n, base.rmse)
        set_aside.add(data, spikes, scale)
        data = without_spikes(data, spikes)
        if np.count_nonzero(spikes) > REFIT_SPIKE_SHARE * data.n or not screened:
            full_problem, screen, screen_base, base = _base_fits(data, screened, screen_base)
        else:
            # a handful of spikes in a long record moves no parameter: the fits keep
            # their values, evaluated on the mended rows
            full_problem = problem_for(data)
            screen = screening_blocks(data, full_problem.d)
            screen_base, base = _evaluate(screen, screen_base), _evaluate(data, base)
        noise = estimate(full_problem)
        commanded = programmed_force(full_problem, noise)
    noise = replace(noise, command=is_command(full_problem, noise, base.residual(), commanded))
    report(0.1, "screening candidate effects")

    # what x's resolution sets through the base model, row by row: every fit from here
    # on weighs each row by the inverse of its error's variance
    errors = velocity = None
    if data.kind == "timeseries":
        velocity = screen_base.problem.velocity_errors(screen_base.params)
        errors = screen_base.problem.resolution_errors(screen_base.params, velocity=velocity)
    weights = input_weights(errors, noise.value,
                            stops=screen_base.problem.stop_rows(screen_base.params)) \
        if errors is not None else None
    full_errors = None
    if weights is not None:
        screen_base = refit(with_weights(screen, weights), screen_base)
        if screened:
            full_errors = full_problem.resolution_errors(base.params)
            data = with_weights(data, input_weights(full_errors, noise.value,
                                                    stops=full_problem.stop_rows(base.params)))
            # the weighted base on every row: the screened solution, evaluated (a
            # polish on every row moves it little and costs a Jacobian per step)
            base = _evaluate(data, screen_base)
        else:
            data, base = screen_base.problem.data, screen_base
        screen = screen_base.problem.data
    # under a commanded force x's reading sets every row's error, and the rows where a
    # jumps are not weighed apart (:meth:`.reweighing.Reweighing.reweigh`)
    search = Selection(screen, noise.value, report, errors, velocity, noise.command)
    available = []
    for effect, why in availability(screen_base.problem).items():
        if why is None:
            available.append(effect)
        else:
            search.verdicts[effect] = Candidate(reason=why)
    current, current_heldout = _search(search, screen_base, available)
    heldout_before = search.heldout_base
    # the search keeps the drop, which a missing effect can distort into an unresolved
    # one; the chosen model's drop is judged
    dropless = unresolved_drop(current, noise.value, earns=search.judgement.needs_drop)
    if dropless:
        # the model without it, with the effects it still needs, and the base model as
        # reported in the same family, so that the errors before and after compare
        current = without_drop(current)
        current, current_heldout = search.backward(current, search.heldout(current),
                                                   keep_one=False)
        # a candidate judged beside the drop may have traded with it (a curved viscous
        # term taking Fc to 0 while Fs holds the level at rest): without the drop each
        # accepted effect's rivals are tried again in its place (no new additions: what
        # the search left out beside the drop stays out)
        if current.effects and not search.white(current):
            current, current_heldout = search.swap(current, current_heldout, available)
            current, current_heldout = search.straighten(current, current_heldout)
        # a drop under a steeper rise never makes the curve fall, and a fit trapped
        # beside the search's drop can misplace one that is there: the chosen effects
        # with a drop fitted afresh, kept where the data determine it and it earns its
        # parameters as an effect does
        found = retried_drop(current, noise.value)
        if found is not None and search.judgement.prefers_drop(current, found[1],
                                                               found[0]) is None:
            retried = found[0]
            retried_heldout = search.heldout(retried)
            search.straightened_beside_drop(current, retried, retried_heldout)
            current, current_heldout, dropless = retried, retried_heldout, None
    # the rows weighed under the chosen model, which may have changed since the
    # search's last acceptance (a curve in place of a line, the drop gone); under the
    # new weights each effect is judged again beside the rest
    reweighed, reweighed_heldout = search.reweigh(current, current_heldout)
    if reweighed is not current:
        current, current_heldout = reweighed, reweighed_heldout
        if len(current.effects) > 1:
            current, current_heldout = search.backward(current, current_heldout)
    if dropless:
        if not screen_base.problem.tied:
            screen_base = without_drop(screen_base)
            heldout_before = search.heldout(screen_base)
            base = refit(data, screen_base, max_nfev=FULL_REFIT_EVALUATIONS) if screened \
                else screen_base
    # each accepted effect's last step (a swap can take an effect out and a later round
    # put it back), in the model's order
    last = {s.effect: s for s in search.steps}
    steps = [last[e] for e in current.effects if e in last]
    if screened and search.reweighed:
        # every row weighed as the search's rows were: where a jumps, and with what v's
        # window sets under the chosen model
        chosen = problem_for(data, current.effects)
        full_errors = full_problem.resolution_errors(
            base.params, velocity=chosen.velocity_errors(current.params))
        jumps = chosen.acceleration_errors(current.params) if search.jumps is not None \
            else None
        data = with_weights(data, input_weights(full_errors, noise.value, jumps,
                                                full_problem.stop_rows(base.params)))
    if screened:
        report(0.92, "refitting the chosen model on every row")
        final = refit(data, current, max_nfev=FULL_REFIT_EVALUATIONS) \
            if current.effects or dropless else base
        steps = [Step(s.effect, final if s.fit is current else _evaluate(data, s.fit),
                      s.evidence, s.heldout) for s in steps]
    else:
        final = current
    if carried is None and final.effects and not commanded:
        late, scale = spike_rows(final.problem, final.residual(), noise.value)
        if late.any():
            set_aside = set_aside or SetAside(data.n, base.rmse)
            set_aside.add(data, late, scale)
            return _diagnose(without_spikes(data, late), progress, set_aside,
                             carried=prepared)
    for name in final.effects:
        search.verdicts[name] = Candidate(final.rmse, final.bic, current_heldout, True, None)
    errors = final.problem.resolution_errors(final.params) \
        if final.problem.kind == "timeseries" else None
    inputs = input_floor(final, noise, errors)
    # what the residual can fall to: the force's noise and what x's resolution sets
    expected = math.hypot(noise.value, inputs)
    white = is_white(final.residual(), final.problem, expected)
    # the rows' misfit in units of their own expected errors (the noise and what x's
    # reading sets, row by row)
    misfit = misfit_ratio(final, noise, inputs, errors)
    if white or (misfit <= UNEXPLAINED_RATIO and inputs >= noise.value) \
            or (misfit > UNEXPLAINED_RATIO and _disturbance_only(final, noise, errors, misfit)):
        # with nothing left that the model lacks, no misfit moves an estimate along a
        # valley of the fit: a correlated parameter is determined where its profile
        # holds. Nor where the rows' misfit is within their own errors and x's reading
        # sets most of them: the structure left is where the reading leaves the
        # prediction open, in rows the fit weighs out (a gearbox's plateaus beside its
        # turns); beside a smaller input floor it is a misfit the weights do not hold,
        # and it moves the estimates (a short record's σ = 167 ± 30 for a truth of 335).
        # Nor where the misfit is large and follows none of the record's variables: a
        # disturbance of the force channel (mains hum), which no parameter follows (a
        # small excess's shares along the variables are not told from chance)
        confirm_correlated(final)
    known = drop_bound_text(final, dropless) if dropless else {}
    beyond = beyond_data(final, noise.value, known)
    for fit in {id(f): f for f in (base, final, *(s.fit for s in steps))}.values():
        mark_beyond(fit, beyond if fit is final else beyond_data(fit, noise.value))
    structure = residual_structure(final.residual(), final.problem, white)
    floor_low = [] if white else floor_low_warnings(final, expected, structure)
    # structure is left where the rows' misfit exceeds their own expected errors
    unexplained = (not white) and not floor_low and misfit > UNEXPLAINED_RATIO
    warnings = list(prepared) + data_warnings(full_problem, noise, inputs) \
        + stick_slip_warnings(full_problem) + search.warnings \
        + beyond_data_warnings(beyond) + fit_warnings(final) \
        + travel_warnings(final, structure) + floor_low
    if set_aside is not None:
        warnings.insert(len(prepared), set_aside.warning(data.kind, data.unit("N")))
    report(1.0, "done")
    return Diagnosis(data, noise, base, final, steps, heldout_before, current_heldout,
                     inputs, white, unexplained, search.verdicts, warnings, structure,
                     screen.n if screened else 0, time.perf_counter() - started)


def _disturbance_only(fit, noise, errors, misfit: float) -> bool:
    """Whether the misfit of ``fit`` follows none of the record's variables
    (:func:`.profile.follows_no_variable`), its residual taken in units of each row's
    expected error, as the misfit is: the rows where x's reading leaves the prediction
    open (a stroke's turns) are not a dependence on where they lie."""
    scaled = scaled_residual(fit, noise, errors)
    residual = fit.residual() if scaled is None else scaled
    return follows_no_variable(residual_structure(residual, fit.problem, False), misfit)


def _base_fits(data: Dataset, screened: bool, start: FitResult | None = None):
    """The problem on every row, the rows screened, and the base fits on both (from
    ``start``'s parameters when given)."""
    full_problem = problem_for(data)
    screen = screening_blocks(data, full_problem.d) if screened else data
    screen_base = base = fit_model(screen, starts=None if start is None else [start.params])
    if screened:
        base = refit(data, screen_base, max_nfev=FULL_REFIT_EVALUATIONS)
    return full_problem, screen, screen_base, base


def _evaluate(data, fit):
    """``fit``'s parameters evaluated on ``data`` without moving them."""
    return fit_model(data, fit.effects, starts=[fit.params], screen=1, max_nfev=1)


__all__ = ["Diagnosis", "diagnose"]
