"""(E6') along a measured x(t)."""

from __future__ import annotations

import weakref
from dataclasses import replace

import numpy as np
from scipy.ndimage import uniform_filter1d

from ...presliding import _presliding_kernel
from ...steady import stribeck_kernel
from ..derivatives import (SHORTEST_WINDOWED, block_velocity, derivatives, position_error,
                           positions, velocity_and_reach, velocity_at, velocity_spread)
from ..local_fits import WINDOWS, acceleration_at
from ..effects import engaged_presliding
from ..kinematics import REVERSAL_STEPS, direction, position_noise, quantum
from ..stickslip import find_stick_slip
from ..stops import find_stops, stop_bounds, stop_mask
from ..strokes import breakaway_places, breakaways_apart, last_reversal
from .base import Problem, Scales, _robust_scale
from .reading import ReadingErrors

#: Kinematics per dataset (a fit builds many problems on one record) ...
_KINEMATICS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: ... and the part of them that t and x alone set, shared by the datasets that differ
#: only in their forces (a record whose spikes were mended)
_MOTION: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
#: A row is in gross sliding when the presliding fraction s·|x − x_r| exceeds this: the
#: body has travelled a quarter of the presliding distance past the point where (E6')
#: reaches the steady curve (a fit that just touches z = 1 at a stroke's end is not).
GROSS_SLIDING_Z = 1.25
#: A record shows the sliding curve only where the body slides at least a whole
#: presliding distance past the point where presliding ends (z = 2): a fit whose (E6')
#: saturates a little before the ends of closed presliding loops has not seen sliding.
SHOWN_SLIDING_Z = 2.0
#: A body in presliding is held when it moves slower than this percentile of its speeds
#: in gross sliding.
HELD_SPEED_PERCENTILE = 10
#: Samples averaged before the direction of a noisy x is read.
NOISY_X_WINDOW = 21


def with_weights(data, weights):
    """``data`` with its rows weighted in a fit (:attr:`~..csvdata.Dataset.weights`),
    sharing the record's kinematics (the weights change no v, a or reversal)."""
    weighted = replace(data, weights=weights)
    if data in _KINEMATICS:
        _KINEMATICS[weighted] = _KINEMATICS[data]
        _MOTION[weighted] = _MOTION[data]
    return weighted


def with_forces(data, forces):
    """``data`` with the forces ``forces`` [N] in place of its own, sharing what its t
    and x set (v, a, the stops and the re-readings of x: :meth:`TimeseriesProblem.once`)."""
    changed = replace(data, columns={**data.columns, "F": forces})
    if data in _MOTION:
        _MOTION[changed] = _MOTION[data]
    return changed


class TimeseriesProblem(ReadingErrors, Problem):
    """(E6') along the measured x(t); what x's reading sets through it, row by row, is
    :class:`.reading.ReadingErrors`'."""

    kind = "timeseries"
    base_names = ("Fc", "Fs", "V", "delta", "s")

    def __init__(self, data, effects=(), fixed=None, ties=None):
        cols = data.columns
        #: the positions as recorded, and (set with the kinematics) the positions the
        #: model runs on: the same for exact x, a local fit of an encoder's counts
        self.t, self.recorded_x = cols["t"], cols["x"]
        self.measured = cols["F"]
        #: independent records (blocks of a screened series): [start, stop) pairs
        edges = [0, *data.segments, data.n]
        self.blocks = list(zip(edges[:-1], edges[1:]))
        self.F0 = data.meta_float("f0", 0.0)
        cached = _KINEMATICS.get(data)
        if cached is None:
            motion = _MOTION.get(data)
            if motion is None:
                motion = _MOTION[data] = self._motion(data.printed.get("x"))
            self.__dict__.update(motion)
            cached = _KINEMATICS[data] = {**motion, **self._forces()}
        self.__dict__.update(cached)
        super().__init__(data, effects, fixed, ties)

    def _motion(self, printed_x: float | None) -> dict:
        """What every model of a record of these t and x shares; computed once per
        dataset (``printed_x``: the unit of x's last printed digit, if known)."""
        #: quantisation step and noise std of x (0: none), its resolution, and the
        #: reversal hysteresis: direction changes within a few resolutions are not real
        self.quantum_x = quantum(self.recorded_x, printed_x)
        self.noise_x = position_noise(self.recorded_x) if self.quantum_x == 0 else 0.0
        self.resolution_x = max(self.quantum_x, self.noise_x)
        self.hysteresis = REVERSAL_STEPS * self.resolution_x
        #: v and a, and how they were taken
        self.x = self.model_positions(self.recorded_x)
        self.derivatives = derivatives(self.t, self.recorded_x, self.quantum_x, self.noise_x,
                                       self.blocks)
        v, a = self.derivatives.v, self.derivatives.a
        error = position_error(self.t, self.recorded_x, self.quantum_x, self.noise_x)
        v_spread = np.concatenate([velocity_spread(self.t[i:j], self.recorded_x[i:j],
                                                   self.resolution_x, error,
                                                   self.derivatives.edges,
                                                   self.derivatives.step_error)
                                   for i, j in self.blocks])
        with np.errstate(divide="ignore"):
            log_speed = np.log(np.abs(v))  # g's argument, reused by every evaluation
        #: the stretches where the body may have halted and turned unseen, and a path
        #: turned in each
        self.stops = find_stops(self.recorded_x, self.blocks, self.quantum_x,
                                self.hysteresis)
        self.d = self.kinematic_direction(self.x)
        path, turned = None, []
        if self.stops:
            dither, directions, turned = self.turned_path()
            dither.flags.writeable = directions.flags.writeable = False  # shared by fits
            path = (dither, directions)
        return {"quantum_x": self.quantum_x, "noise_x": self.noise_x, "stops": self.stops,
                "stop_mask": stop_mask(self.x.size, self.stops),
                "stop_path": path, "turned_spans": turned,
                "resolution_x": self.resolution_x, "hysteresis": self.hysteresis, "x": self.x,
                "derivatives": self.derivatives, "v": v, "v_spread": v_spread,
                "log_speed": log_speed, "a": a, "d": self.d}

    def _forces(self) -> dict:
        """What every model of this record shares that its forces set too: the scales,
        and how far the measured force bounds what a turn in a stop changed."""
        steps = np.abs(np.diff(self.x))
        moving = steps[steps > 0]
        scales = Scales(
            force=_robust_scale(self.measured),
            speed=_robust_scale(self.v),
            travel=float(np.ptp(self.x)) or 1.0,
            duration=float(self.t[-1] - self.t[0]) or 1.0,
            accel=_robust_scale(self.a),
            step=max(float(np.median(moving)) if moving.size else 1.0, self.quantum_x),
        )
        bounds = stop_bounds(self.measured, self.turned_spans) if self.stops else None
        return {"scales": scales, "stop_bounds": bounds}

    def model_positions(self, recorded):
        """The positions the model runs on for a record of these samples
        (:func:`..derivatives.positions`, block by block)."""
        return np.concatenate([positions(self.t[a:b], recorded[a:b], self.resolution_x)
                               for a, b in self.blocks])

    def kinematic_velocity(self, x):
        """v of another position record of the same samples (the body behind a play, x
        dithered by its resolution), taken as the record's own v is."""
        return block_velocity(self.t, x, self.resolution_x, self.blocks,
                              self.derivatives.edges, self.derivatives.step_error)

    def body_velocity(self, body, engaged):
        """:meth:`kinematic_velocity` of the body behind a play, ``body`` [m], engaged
        where it rides an edge of the play. Wherever everything a sample's window reads
        rides one edge, the body follows the model's positions at a constant offset,
        which no line's slope sees: its v is theirs, and only the other samples' is
        taken again (a play's fit evaluates the body's v hundreds of times)."""
        if self.derivatives.edges or self.resolution_x <= 0:
            return self.kinematic_velocity(body)
        reference, reach = self.once("model positions' velocity", self._velocity_and_reach,
                                     motion=True)
        side = np.where(engaged, np.sign(body - self.x), 0.0)
        # a run of rows on one edge; a free row is a run of its own
        runs = np.cumsum(np.r_[True, (side[1:] != side[:-1]) | (side[1:] == 0.0)])
        first, last = reach[:, 0], reach[:, 1]
        moved = (runs[first] != runs[last]) | (side[first] == 0.0)
        out = np.empty(body.size)
        for a, b in self.blocks:
            if b - a < SHORTEST_WINDOWED:
                out[a:b] = self._block_velocity(body, a, b)
            else:
                out[a:b] = velocity_at(self.t[a:b], body[a:b], self.resolution_x,
                                       np.flatnonzero(moved[a:b]), reference[a:b],
                                       self.derivatives.step_error)
        return out

    def _velocity_and_reach(self):
        """v of the model's positions and each sample's reach (:func:`velocity_and_reach`,
        block by block, in the record's rows); a short block's reach is itself."""
        v, reach = np.empty(self.x.size), np.empty((self.x.size, 2), dtype=np.int64)
        for a, b in self.blocks:
            if b - a < SHORTEST_WINDOWED:
                v[a:b], reach[a:b] = self._block_velocity(self.x, a, b), (a, b - 1)
            else:
                v[a:b], local = velocity_and_reach(self.t[a:b], self.x[a:b],
                                                   self.resolution_x,
                                                   self.derivatives.step_error)
                reach[a:b] = local + a
        return v, reach

    def _block_velocity(self, x, a, b):
        """v of block [a, b) of another position record, taken as the record's own is."""
        return block_velocity(self.t, x, self.resolution_x, [(a, b)], self.derivatives.edges,
                              self.derivatives.step_error)

    def kinematic_acceleration(self, x):
        """a of another position record of the same samples, taken as the record's own
        a is (the same window, block by block)."""
        if self.derivatives.method == "gradient":
            return np.concatenate([np.gradient(np.gradient(x[a:b], self.t[a:b]), self.t[a:b])
                                   for a, b in self.blocks])
        windows = self.derivatives.windows
        return np.concatenate([
            acceleration_at(self.t[a:b], x[a:b], windows[a:b]) if b - a >= WINDOWS[0]
            else np.gradient(self._block_velocity(x, a, b), self.t[a:b])
            for a, b in self.blocks])

    def kinematic_direction(self, x, hysteresis=None):
        """Directions of a position record of the same samples, with this record's
        reversal hysteresis unless another is given."""
        hysteresis = self.hysteresis if hysteresis is None else hysteresis
        if self.noise_x > 0 and hysteresis > 0:
            # Gaussian noise has no largest excursion: the trigger runs on x averaged
            # over 21 samples, where the noise std is 4.6× smaller than the hysteresis'
            x = uniform_filter1d(x, NOISY_X_WINDOW, mode="nearest")
        return np.concatenate([direction(x[a:b], hysteresis) for a, b in self.blocks])

    def _presliding(self, ctx, target, s):
        """(E6') block by block; a later block starts from its measured force."""
        out = np.empty(self.x.size)
        for a, b in self.blocks:
            F0 = self.F0 if a == 0 else float(self.measured[a])
            x, d = ctx["x"][a:b], ctx["d"][a:b]
            if ctx["engaged"] is None:
                out[a:b] = _presliding_kernel(x, d, target[a:b], s, F0)
            else:
                out[a:b] = engaged_presliding(x, d, target[a:b], s, F0, ctx["engaged"][a:b])
        return out

    @property
    def reversals(self) -> int:
        return int(np.count_nonzero(np.diff(self.d)))

    def predict(self, p, dither=None, sensor=True, directions=None, velocity=None):
        """Predicted force [N]; ``dither`` [m] is added to the positions (velocities
        follow unless ``velocity`` is given: a reading's own; the directions stay unless
        ``directions`` are given), to propagate the resolution of x. ``sensor=False``
        leaves out what the sensor adds (offset, inertia, …): the friction alone."""
        ctx = {"x": self.x, "v": self.v, "d": self.d, "engaged": None}
        if dither is not None:
            ctx["x"] = self.x + dither
            ctx["v"] = self.kinematic_velocity(ctx["x"]) if velocity is None else velocity
            if any(effect.reads_acceleration for effect in self.effect_objects):
                ctx["a"] = self.kinematic_acceleration(ctx["x"])
        if directions is not None:
            ctx["d"] = directions
        for effect in self.effect_objects:
            ctx = effect.body_motion(self, p, ctx)
        v_slip = ctx["v"]
        for effect in self.effect_objects:
            v_slip = effect.slip_velocity(self, p, v_slip)
        Fc, Fs = self._levels(p, ctx["d"] < 0)
        log_speed = self.log_speed if v_slip is self.v else None
        g = self._scaled(p, stribeck_kernel(v_slip, Fc, Fs, p["V"], p["delta"], log_speed))
        target = ctx["d"] * g
        for effect in self.effect_objects:
            target = target + effect.target(self, p, ctx["v"])
        F = self._presliding(ctx, np.asarray(target, dtype=float), p["s"])
        if not sensor:
            return F
        for effect in self.effect_objects:
            F = effect.sensor(self, p, F, ctx)
        return F

    def _scaled(self, p, g):
        """``g`` scaled as the effects scale the Stribeck magnitude (a drift)."""
        for effect in self.effect_objects:
            g = effect.scale_g(self, p, g)
        return g

    def sliding_rows(self):
        speed = np.abs(self.v)
        return speed >= np.median(speed)

    def regressor_speed(self):
        return self.v

    def signed_direction(self):
        return self.d

    def direction_counts(self):
        moving = np.abs(self.v) >= 0.05 * self.scales.speed
        d = self.d[moving]
        return int(np.count_nonzero(d > 0)), int(np.count_nonzero(d < 0)), int(d.size)

    def _last_reversal(self):
        """Index of the sample before each row's last reversal (0 before the first)."""
        return last_reversal(self.d)

    def once(self, key, compute, motion=False):
        """What ``compute()`` gives, computed once per dataset and kept with its
        kinematics: for what the record alone sets, whatever the model's parameters
        (``motion``: what its t and x alone set, once for every dataset that shares
        them, :func:`with_forces`)."""
        cached = (_MOTION if motion else _KINEMATICS)[self.data]
        if key not in cached:
            cached[key] = compute()
        return cached[key]

    @property
    def stick_slip(self):
        """The record's stick-slip cycle (:mod:`..stickslip`), or None; found once per
        dataset."""
        return self.once("stick_slip",
                         lambda: find_stick_slip(self.t, self.recorded_x, self.measured))

    def presliding_fraction(self, params) -> np.ndarray:
        """z = s·|x − x_r| of each row under ``params`` (x_r at the last reversal)."""
        last, _ = self._last_reversal()
        return params["s"] * np.abs(self.x - self.x[last])

    def gross_sliding(self, params) -> np.ndarray:
        """Rows in gross sliding under ``params`` (:data:`GROSS_SLIDING_Z`)."""
        return self.presliding_fraction(params) >= GROSS_SLIDING_Z

    def curve_speeds(self, params):
        z = self.presliding_fraction(params)
        if not np.max(z, initial=0.0) >= SHOWN_SLIDING_Z:
            return np.empty(0)
        return np.abs(self.v[z >= GROSS_SLIDING_Z])

    def sliding_each_way(self, params) -> tuple[int, int]:
        """Rows in gross sliding (as :meth:`curve_speeds` counts them) moving positive
        and moving negative."""
        z = self.presliding_fraction(params)
        if not np.max(z, initial=0.0) >= SHOWN_SLIDING_Z:
            return 0, 0
        sliding = z >= GROSS_SLIDING_Z
        return int(np.count_nonzero(sliding & (self.d > 0))), \
            int(np.count_nonzero(sliding & (self.d < 0)))

    def breakaway_places(self, params) -> tuple[np.ndarray, np.ndarray]:
        """x [m] where each direction breaks away under ``params``
        (:func:`..strokes.breakaway_places`)."""
        return breakaway_places(self.x, self.d, self.presliding_fraction(params),
                                GROSS_SLIDING_Z)

    def breakaways_apart(self, params) -> bool:
        """Whether each direction breaks away at one place of its own under ``params``
        (:func:`..strokes.breakaways_apart`)."""
        return breakaways_apart(*self.breakaway_places(params))

    def held_force(self, params):
        """The largest friction measured each way (the force less what the sensor adds:
        an inertial m·a is no friction held) where the body is held: the fitted
        presliding has not reached the steady curve (z < 1), and the body moves slower
        than nearly all of its gross sliding (a break-away under way is not held). In
        the levels at the record's start, where an effect scales g (a drift)."""
        z = self.presliding_fraction(params)
        held = z < 1.0
        sliding = np.abs(self.v[z >= GROSS_SLIDING_Z])
        if sliding.size:
            held &= np.abs(self.v) < np.percentile(sliding, HELD_SPEED_PERCENTILE)
        if not held.any():
            return None
        added = self.predict(params) - self.predict(params, sensor=False)
        # a force held late in a record whose friction grows (a drift) bounds the
        # start's levels by what it was then: each row's friction over its scale
        friction = ((self.measured - added) / self._scaled(params, np.ones(self.x.size)))[held]
        return max(float(np.max(friction)), 0.0), max(float(-np.min(friction)), 0.0)

    def after_reversal(self, reach):
        """Rows within ``reach`` [m] of their last reversal (none before the first)."""
        last, reversed_ = self._last_reversal()
        return (np.abs(self.x - self.x[last]) <= reach) & reversed_

    def variables(self):
        last, _ = self._last_reversal()
        return {"x": self.x, "x - x_r": self.x - self.x[last], "v": self.v, "t": self.t,
                "time since reversal": self.t - self.t[last], "direction": self.d}
