"""What the reading of x sets through the time-series model, row by row.

A mixin of :class:`.timeseries.TimeseriesProblem`: the record read again the way it was
read (an encoder's counts at another phase, or the same noise), the turns a stop can
hide, where a's local fit spreads a jump, and where v's window mixes in a change of
speed. Each is a force error [N] per row; together they weigh the rows of a fit and a
judgement (:func:`..input_error.input_weights`) and make the report's ``input_floor``.
"""

from __future__ import annotations

import numpy as np

from ..local_fits import smooth_fit

#: Readings of the smoothed record that estimate what the resolution of x does.
RESOLUTION_DRAWS = 4
#: The jitter of an encoder's reading at a count boundary, in counts (its electronics).
FLICKER = 0.25
#: The short of the two smoothings of the record [samples] (a quick turn survives it).
SHORT_SMOOTHING = 13
#: The share of the rows outside stops in gross sliding for a record to slide between
#: its stops (:meth:`ReadingErrors._slides_between_stops`).
SLIDING_BETWEEN_STOPS = 0.5


class ReadingErrors:
    """Each row's force error that x's reading sets, for a problem with the record's
    kinematics (``t``, ``x``, ``recorded_x``, ``v``, ``d``, ``v_spread``, ``stops``, …)
    and ``predict``."""

    def resolution_noise(self, params, seed=0) -> float:
        """RMS force error [N] that the resolution of x alone causes in the model.

        The record is smoothed (the local quadratic of :mod:`..derivatives`), and the
        model run on that path with its own reversals is compared with the model run
        on the path read again the way the record was read — by an encoder of the same
        step at a random phase (each reading keeps its error while the body stays
        within a count, as real counts do), or with the same noise std — with the
        reversals this engine finds in such a reading. Both parts count: (E6') is
        steepest just after a reversal, where a count of x_r moves F most. The path is
        smoothed at two scales, the acceleration's window and
        :data:`SHORT_SMOOTHING` samples, and the smaller error is taken: a smoothing
        too long hides a quick turn, one too short keeps the steps of slow motion in
        the "exact" path, and either only adds to the estimate.
        """
        return float(np.sqrt(np.mean(np.square(self.resolution_errors(params, seed)))))

    def resolution_errors(self, params, seed=0, velocity=None) -> np.ndarray:
        """Each row's RMS force error [N] that the resolution of x causes in the model
        (:meth:`resolution_noise`, row by row): largest just after reversals, where
        (E6') is steep, in stops, where the body may have turned unseen
        (:meth:`_stop_errors`), and where the speed changes within the window v is
        taken over (:meth:`velocity_errors`, or ``velocity``, another model's); zero
        for exact x."""
        if self.resolution_x == 0:
            return np.zeros(self.x.size)
        reading = min((self._reading_errors(params, window, seed)
                       for window in {SHORT_SMOOTHING, self.derivatives.window}),
                      key=lambda rows: float(np.mean(np.square(rows))))
        if velocity is None:
            velocity = self.velocity_errors(params)
        return np.hypot(np.hypot(reading, self._stop_errors(params)), velocity)

    def velocity_errors(self, params) -> np.ndarray:
        """Each row's force error [N] in gross sliding from where v's window lies
        (:func:`..derivatives.velocity_spread`): half the change of what the effects
        add to the steady force in the row's direction (a viscous rise) between speeds
        |v| raised and lowered by the spread. A re-reading of the record
        (:meth:`_reading_errors`) takes v over the same windows as the record does and
        cannot show it: a gearbox's plateaus at 0.1 rad/s, next to turns, read 40 %
        slow, where σ·|v|ⁿ with n = 0.36 is steep. Not the Stribeck drop's: weighed by
        its own slope, the rows that would show a drop absent count for less wherever
        a fit puts one (strokes of a dry slide then "resolved" 2 % of drop at
        0.1 mm/s). In presliding the force follows x, not v, and the re-reading holds
        what x's reading sets there."""
        if not self.v_spread.any() or not self.effect_objects:
            return np.zeros(self.x.size)
        sliding = self.gross_sliding(params)
        speed = np.abs(self.v)
        faster = self.d * (speed + self.v_spread)
        slower = self.d * np.maximum(speed - self.v_spread, 0.0)
        change = sum(effect.target(self, params, faster) - effect.target(self, params, slower)
                     for effect in self.effect_objects)
        return np.where(sliding, 0.5 * np.abs(change), 0.0)

    def stop_rows(self, params) -> np.ndarray | None:
        """Rows within a stop (:func:`..stops.find_stops`) where the body slides between
        its stops under ``params`` (:meth:`_slides_between_stops`), or None."""
        if self.stop_mask is None or not self._slides_between_stops(params):
            return None
        return self.stop_mask

    def _slides_between_stops(self, params) -> bool:
        """Whether the body slides where it is not stopped: at least
        :data:`SLIDING_BETWEEN_STOPS` of the other rows in gross sliding under
        ``params``. A presliding test never slides far past its presliding distance;
        every row of it is presliding, its stops are no less informative than the rest,
        and what the reading leaves open there is the re-reading's to say."""
        sliding = self.gross_sliding(params)[~self.stop_mask]
        return sliding.size > 0 and float(np.mean(sliding)) >= SLIDING_BETWEEN_STOPS

    def _stop_errors(self, params) -> np.ndarray:
        """Each row's force error [N] from turns the reading cannot see: a body that
        halts within a count (or within the reversal hysteresis) may turn there unseen,
        and its friction then runs down the presliding curve through what the record
        does not show. The difference between the model on the record's path and on the
        path turned at each stop (:meth:`turned_path`), never more than the measured
        force says such a turn changed (:func:`..stops.stop_bounds`, over the rows where
        the two paths differ)."""
        if self.stop_rows(params) is None:
            return np.zeros(self.x.size)
        dither, directions = self.stop_path
        velocity = self.once("stop path velocity",
                             lambda: self.kinematic_velocity(self.x + dither), motion=True)
        difference = np.abs(self._predict_reading(params, dither, directions, velocity)
                            - self.predict(params))
        return np.minimum(difference, self.stop_bounds)

    def turned_path(self):
        """The path that turns at the start of each stop (:func:`..stops.find_stops`)
        and moves back through the stop's span (at least half a count), with the rows
        after it, which re-engage from the turn back at the stop's end: the dither [m]
        to the record's path, its directions, and the [start, stop) of the rows where
        it departs from the record's. Where the reading leaves a count back the way it
        came (:meth:`_turned_inside`), the path keeps moving back after the stop for as
        long as the record's directions still wait for the reversal hysteresis: a path
        turned back there that then followed the record's old direction would turn
        twice. The record's alone (its stops, directions and path), so taken once with
        its kinematics."""
        dither = np.zeros(self.x.size)
        directions = self.d.copy()
        spans = []
        for (a, b), turned in zip(self.stops, self._turned_inside()):
            back = max(float(np.ptp(self.recorded_x[a:b])), 0.5 * self.quantum_x)
            dither[a:b] = -self.d[a] * back * np.linspace(0.0, 1.0, b - a) \
                - (self.x[a:b] - self.x[a])
            directions[a:b] = -self.d[a]
            if turned:
                # the body left the count back the way it came: it moves so until the
                # record's directions, which wait for the reversal hysteresis, turn too,
                # along the record's path from where the turned one left the stop
                moved = np.flatnonzero(self.d[b:turned] != self.d[a])
                end = b + (int(moved[0]) if moved.size else turned - b)
                directions[b:end] = -self.d[a]
                dither[b:end] = (self.x[b - 1] + dither[b - 1] - self.x[b]) \
                    * np.linspace(1.0, 0.0, end - b)
                b = max(b, end)
            spans.append((a, b))
        return dither, directions, spans

    def _turned_inside(self) -> list[int]:
        """For each stop, where the reading holds one count and leaves it back to the
        count it came from (the body turned inside it), the row up to which the record
        may still wait to turn: the next stop's start, the end of the block, or where
        the reading comes back into that count; 0 for the other stops."""
        out = []
        starts = [a for a, _ in self.stops[1:]] + [self.x.size]
        for (a, b), following in zip(self.stops, starts):
            first, stop = next((i, j) for i, j in self.blocks if i <= a < j)
            inside = self.recorded_x[a:b]
            turned = first < a and b < stop and float(np.ptp(inside)) == 0.0 \
                and self.recorded_x[a - 1] == self.recorded_x[b]
            if not turned:
                out.append(0)
                continue
            # ... or where the reading comes back into that count
            until = min(following, stop)
            back_in = np.flatnonzero(self.recorded_x[b:until] == inside[0])
            out.append(b + int(back_in[0]) if back_in.size else until)
        return out

    def acceleration_errors(self, params) -> np.ndarray | None:
        """Each row's force error [N] where a jumps, which no reading at the record's
        own windows shows (:meth:`resolution_errors` leaves it out): the local fit
        spreads the jump over its window
        (:attr:`..derivatives.Derivatives.bias`), and an effect that reads a (an
        inertia's m_e) carries it into the force. None where no effect reads a or a is
        not taken by local fits."""
        gain = sum(effect.acceleration_gain(self, params) for effect in self.effect_objects)
        if not gain or self.derivatives.bias is None:
            return None
        return gain * self.derivatives.bias

    def _reading_errors(self, params, window: int, seed: int) -> np.ndarray:
        readings = self._readings(window, seed)
        # the path's own reversals: any turn the reading could resolve at all
        exact = self._predict_reading(params, *next(readings))
        errors = [self._predict_reading(params, *reading) - exact for reading in readings]
        return np.sqrt(np.mean(np.square(errors), axis=0))

    def _predict_reading(self, params, dither, directions, velocity) -> np.ndarray:
        return self.predict(params, dither, directions=directions, velocity=velocity)

    def _readings(self, window: int, seed: int):
        """The smoothed record, then each of its :data:`RESOLUTION_DRAWS` readings, as
        ``predict``'s dither [m], directions and velocity [m/s]. They are the record's
        alone; the velocities, which take most of the time, are kept with its
        kinematics (:meth:`~.timeseries.TimeseriesProblem.once`), the rest drawn again
        from the same seed."""
        velocities = self.once(("reading velocities", window, seed), list, motion=True)
        rng = np.random.default_rng(seed)
        smooth = np.concatenate([
            smooth_fit(self.t[a:b], self.recorded_x[a:b], window)[0] if b - a >= window
            else self.recorded_x[a:b] for a, b in self.blocks])
        if not velocities:
            velocities.append(self.kinematic_velocity(smooth))
        yield (smooth - self.x, self.kinematic_direction(smooth, 0.5 * self.resolution_x),
               velocities[0])
        for draw in range(1, RESOLUTION_DRAWS + 1):
            if self.quantum_x > 0:
                # a random phase of the grid, and the flicker of a count boundary: an
                # encoder at rest near one reads either count (a quarter count of jitter)
                phase = rng.uniform(0.0, self.quantum_x)
                jitter = FLICKER * self.quantum_x * rng.standard_normal(smooth.size)
                read = self.quantum_x * np.round((smooth - phase + jitter) / self.quantum_x) \
                    + phase
            else:
                read = smooth + self.noise_x * rng.standard_normal(smooth.size)
            # the reading goes through what this engine does with a record
            path = self.model_positions(read)
            if len(velocities) == draw:
                # v through an encoder's edges needs the counts themselves, as the record's
                velocities.append(self.kinematic_velocity(read if self.derivatives.edges
                                                          else path))
            yield path - self.x, self.kinematic_direction(path), velocities[draw]


__all__ = ["ReadingErrors"]
