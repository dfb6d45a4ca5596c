"""The rows of a search weighed again under the model it has accepted.

A mixin of :class:`.selection.Selection` (its ``errors``, ``velocity``, ``jumps``,
``command``, ``noise``, ``data``, ``judgement`` and ``restarts``): what x's reading
sets through the model depends on the model, and the rows' weights follow it
(:func:`.input_error.input_weights`).
"""

from __future__ import annotations

import numpy as np

from .fitting import best_base_starts, refit
from .input_error import input_weights
from .models import with_weights

#: The rows are weighed again under an accepted model where the error its speed's
#: uncertainty sets changes by more than this share (or this share of the noise floor)
#: on some row (:meth:`Reweighing.reweigh`).
REWEIGH_CHANGE = 0.1


class Reweighing:
    """Weighs a search's rows again under its accepted models."""

    def reweigh(self, current, current_heldout):
        """The rows weighed again under the accepted model, where it changes what their
        input sets (the effective variance of errors in both variables).

        Where the model's force changes with speed (a viscous rise), a row whose v its
        window cannot fix (:meth:`~.models.timeseries.TimeseriesProblem.velocity_errors`)
        counts for less: under the base model a gearbox's curve is flat on its plateaus,
        and the rows beside its turns, read 40 % slow, drew σ·|v|ⁿ to n = 0.54 (truth
        0.36) and Fc 30 % high. Under a commanded force too: x's reading sets every
        row's error there, and a DAC's servo whose slow rows its counts leave open named
        a curve of n = 0.2–0.5 for its straight viscous rise, with Fc a third of the
        truth.

        Once the model reads the acceleration (an inertia), the rows where a jumps
        (a carriage's start and braking) are weighed by the error a's local fit makes
        there, in the fits as in the judgement: the fit spreads the jump over its window,
        and m_e times that error, tens of newtons on a handful of rows, would otherwise
        be most of every later candidate's cost (a viscous rise of 3 N beside a load
        cell of 0.5 N refused for an RMSE "falling by only 1.5 %"). Not under a
        commanded force: there the noise floor is the command's step, x's reading sets
        every row's error, and what the jump rows had hidden, the presliding shape the
        library lacks, passed as an asymmetry or a play on 3 of 5 torque ramps of a
        joint. Nor where the body sticks and slips: there every slip starts and ends
        with a jump of a, the slips are all the sliding the record holds, and weighing
        their rows apart set aside half of them (a dragged stage then named a viscous
        rise with Fc on its bound, where its friction is a plain Stribeck curve)."""
        if self.errors is None:
            return current, current_heldout
        jumps = self.jumps
        if jumps is None and current.problem.stick_slip is None and not self.command:
            found = current.problem.acceleration_errors(current.params)
            jumps = found if found is not None and found.any() else None
        velocity = current.problem.velocity_errors(current.params)
        if jumps is self.jumps and np.allclose(velocity, self.velocity, rtol=REWEIGH_CHANGE,
                                               atol=REWEIGH_CHANGE * self.noise):
            return current, current_heldout
        reading = np.sqrt(np.maximum(self.errors**2 - self.velocity**2, 0.0))
        self.errors, self.velocity = np.hypot(reading, velocity), velocity
        self.reweighed, self.jumps = True, jumps
        stops = current.problem.stop_rows(current.params)
        self.data = with_weights(self.data, input_weights(self.errors, self.noise, jumps, stops))
        self.judgement.reweigh(self.data, jumps is not None)
        self.restarts = best_base_starts(self.data)
        current = refit(self.data, current)
        return current, self.heldout(current)


__all__ = ["REWEIGH_CHANGE", "Reweighing"]
