"""The measurement noise, estimated without any model (the report's ``noise_floor``).

- Rows that share their regressor (repeats: the same speed, or the same rate, direction
  and dwell) give the noise directly: the pooled within-group standard deviation. Where
  the data have enough repeats this is the estimate, whatever the other estimators say.
- Otherwise F is taken as smooth along its regressor (time, speed, rate): robust (MAD)
  second and third differences; each is unbiased for white noise and too high where F
  curves, so the smaller is taken.
- The floor never exceeds what a smooth function of the regressor leaves of F: a steady
  curve's set-points are spaced unevenly (often geometrically), and where a gearbox's
  σ·|v|ⁿ rises steeply between the last few, differences along them read the curve as
  noise (:func:`smooth_sigma`).
- A force computed from the encoder's reading steps where the reading ticks: what it
  carries from x (:func:`carried_from_x`) is noise of the column too, and the floor is
  never below it.
- Never below the quantisation of the force column, ``q/√12``.

The floor is the noise of the measured force alone. A force column that is noise-free
(a commanded force: the noise sits in x, :func:`is_command`) has the floor of its own
resolution. What the resolution of x adds to the prediction error through the model is
a different thing, the ``input_floor`` (:mod:`.input_error`): it is reported beside the
floor, never added to it, and never a reason to refuse an effect.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from math import comb

import numpy as np

from .local_fits import smooth_fit
from .kinematics import printed_unit, quantum

_MAD_TO_STD = 1.4826
#: Repeats give the floor when at least this share of rows (and 6) have a repeat.
MIN_REPLICATED_SHARE = 0.3
#: A force column whose differences are below this share of the residual's is a command.
COMMAND_RATIO = 0.1
#: ... or below this share of the force scale.
COMMAND_RELATIVE = 1e-6
#: A force column with no noise above its resolution whose changes turn less often than
#: this is programmed (noise turns half of the time or more).
COMMAND_TURNS = 0.1
#: ... and whose changes turn less often than this is programmed whatever its
#: resolution (a programmed ramp less a model of the position it reads).
SMOOTH_TURNS = 0.02
#: Changes a column needs before their turns are counted.
MIN_CHANGES = 20
#: Every how many rows a time series' differences are also taken (:func:`orderings`).
DECIMATIONS = (2, 3)
#: A force whose second differences are this many times rougher (MAD) at the rows where
#: x's reading ticks than between them carries x's steps (:func:`carried_from_x`) ...
TICK_ROUGHNESS = 3.0
#: ... judged where each kind of row holds at least this many rows.
MIN_TICK_ROWS = 100
#: A force whose fast part a filter of x's explains this well is computed from x ...
CONTROLLER_R2 = 0.9
#: ... over this many samples of x's history ...
CONTROLLER_LAGS = 16
#: ... the fast parts being what a local quadratic over this many samples leaves.
FAST_WINDOW = 9
#: The highest degree of the polynomial in ln|v| that :func:`smooth_sigma` fits to one
#: direction of a steady curve (the degree is chosen by generalised cross-validation) ...
SMOOTH_MAX_DEGREE = 9
#: ... keeping at least this many rows more than its coefficients.
SMOOTH_SPARE_ROWS = 4


@dataclass
class NoiseFloor:
    """The estimate and how it was made.

    ``method`` is ``"replicates"``, ``"differences"``, ``"smooth fit"``
    (:func:`smooth_sigma`), ``"carried from x"``
    (:func:`carried_from_x`) or ``"quantisation"``;
    ``quantum_F`` the step of the force column (0 if none); ``smooth_F`` the differences
    estimate of F alone; ``command`` whether the force column is a command
    (:func:`is_command`).
    """

    value: float
    method: str
    quantum_F: float = 0.0
    smooth_F: float = math.nan
    replicated_rows: int = 0
    command: bool = False


def _replicate_sigma(F, keys, nuisance=None):
    """Pooled within-group std of rows sharing ``keys``, and the replicated row count.

    With ``nuisance`` (a second factor, e.g. dwell, that varies inside the groups), the
    groups and the nuisance levels are fitted as additive means and the std comes from
    what is left (a two-way layout), so a nuisance effect is not counted as noise.
    """
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    replicated = counts[inverse] >= 2
    rows = int(replicated.sum())
    if rows < max(6, MIN_REPLICATED_SHARE * F.size):
        return math.nan, rows
    if nuisance is None or np.unique(nuisance).size < 2:
        means = np.bincount(inverse, F) / counts
        dev = F[replicated] - means[inverse[replicated]]
        dof = rows - np.count_nonzero(counts >= 2)
        return float(math.sqrt(np.dot(dev, dev) / max(dof, 1))), rows
    sel = np.flatnonzero(replicated)
    groups = np.unique(inverse[sel], return_inverse=True)[1].ravel()
    levels = np.unique(nuisance[sel], return_inverse=True)[1].ravel()
    design = np.zeros((sel.size, groups.max() + 1 + levels.max()))
    design[np.arange(sel.size), groups] = 1.0
    extra = levels > 0  # the first level is the reference
    design[np.flatnonzero(extra), groups.max() + levels[extra]] = 1.0
    coef, _, rank, _ = np.linalg.lstsq(design, F[sel], rcond=None)
    dev = F[sel] - design @ coef
    dof = sel.size - rank
    if dof < 3:
        return math.nan, rows
    return float(math.sqrt(np.dot(dev, dev) / dof)), rows


def replicate_keys(problem) -> list[tuple[np.ndarray, np.ndarray | None]]:
    """Ways rows can repeat one another: (keys that must agree, nuisance factor)."""
    if problem.kind == "steady":
        return [(problem.v[:, None], None)]
    if problem.kind == "breakaway":
        # rows repeat one another when rate, direction and dwell agree; failing that,
        # rows at one rate and direction, with dwell as an additive nuisance factor
        return [(np.column_stack([problem.k, problem.direction, problem.dwell]), None),
                (np.column_stack([problem.k, problem.direction]), problem.dwell)]
    return []


def orderings(problem) -> list[list[np.ndarray]]:
    """Ways to split the rows into groups ordered by the regressor, inside which F varies
    smoothly; the first is the finest. A time series is also taken every
    :data:`DECIMATIONS`-th row: a disturbance near half the sampling rate (mains hum
    logged at 100 Hz) alternates from row to row like noise, and differences see it at
    up to 2.4 times its RMS; every second or third row it is a slow wave that they
    pass."""
    if problem.kind == "timeseries":
        rows = np.arange(problem.data.n)
        return [[rows]] + [[rows[start::step] for start in range(step)]
                           for step in DECIMATIONS]
    if problem.kind == "steady":
        order = np.argsort(problem.v, kind="stable")
        v = problem.v[order]
        return [[order[v < 0], order[v > 0]]]
    keys = np.column_stack([problem.direction, problem.dwell])
    order = np.lexsort((problem.k, problem.dwell, problem.direction))
    fine = [order[np.all(keys[order] == key, axis=1)] for key in np.unique(keys, axis=0)]
    order = np.lexsort((problem.k, problem.direction))
    coarse = [order[problem.direction[order] == value] for value in np.unique(problem.direction)]
    return [fine, coarse]


def difference_sigma(values, groupings) -> float:
    """Smallest robust noise estimate from 2nd and 3rd differences along ``groupings``."""
    estimates = []
    for groups in groupings:
        for order in (2, 3):
            diffs = [np.diff(values[g], order) / math.sqrt(comb(2 * order, order))
                     for g in groups if g.size > order + 2]
            if diffs:
                e = np.concatenate(diffs)
                estimates.append(_MAD_TO_STD * float(np.median(np.abs(e))))
    return min(estimates) if estimates else math.nan


def smooth_sigma(problem) -> float:
    """The noise std [N] that a smooth function of the regressor leaves of F: for a
    steady curve, per direction, a polynomial in ln|v| (the Stribeck drop and a power
    law are smooth there) of the degree that minimises the generalised cross-validation
    score ``n·RSS/(n − p)²``, the residual pooled with its degrees of freedom. NaN for
    other kinds, or where no direction has rows to spare.

    Unlike differences along the rows it does not take the curve's bend between widely
    spaced set-points for noise, and it is unbiased where the polynomial holds the
    curve; where it does not, it is too high, and the floor keeps the smaller estimate.
    """
    if problem.kind != "steady":
        return math.nan
    v, F = problem.v, problem.measured
    rss, spent, rows = 0.0, 0, 0
    for side in (v < 0, v > 0):
        n = int(np.count_nonzero(side))
        degrees = range(1, min(SMOOTH_MAX_DEGREE, n - SMOOTH_SPARE_ROWS - 1) + 1)
        if not degrees:
            continue
        u = np.log(np.abs(v[side]))
        u = (u - u.mean()) / (u.std() or 1.0)
        best = None
        for degree in degrees:
            fitted = np.polynomial.polynomial.Polynomial.fit(u, F[side], degree)
            part = float(np.sum((F[side] - fitted(u)) ** 2))
            score = n * part / (n - degree - 1) ** 2
            if best is None or score < best[0]:
                best = (score, part, degree + 1)
        rss, spent, rows = rss + best[1], spent + best[2], rows + n
    return math.sqrt(rss / (rows - spent)) if rows > spent else math.nan


def carried_from_x(problem) -> float:
    """The noise [N] a force column carries from the position's reading: 0 for a
    measured force.

    A force computed from the encoder's reading (a programmed torque less a gravity
    model, an observer's estimate) steps wherever the reading ticks, by the model's
    slope times one count, while the true force knows nothing of the encoder; a
    sensor's noise is as rough at those rows as between them. So where F's second
    differences are :data:`TICK_ROUGHNESS` times rougher (MAD) at the rows beside a tick
    than at the others, the column holds ``−g'(x)·e``, e the reading's error (one count
    wide, uniform), and its std is ``rms(J)/√12`` for the steps J; each step J puts ±J
    into the two second differences beside it, so ``rms(J)²/12 = (ms_tick −
    ms_other)·6/12`` over the normalised differences. This is the noise of F alone, as
    the column holds it, whatever model is fitted: differences alone miss it where the
    body moves slower than a count a row (the error is then a slow sawtooth that they
    pass between its steps)."""
    if problem.kind != "timeseries" or not getattr(problem, "quantum_x", 0.0) > 0:
        return 0.0
    F = problem.measured
    ticks = np.diff(problem.recorded_x) != 0
    beside = ticks[1:] | ticks[:-1]  # the rows of F's second differences
    if min(np.count_nonzero(beside), np.count_nonzero(~beside)) < MIN_TICK_ROWS:
        return 0.0
    second = np.diff(F, 2) / math.sqrt(6)
    at, between = second[beside], second[~beside]
    mad_at, mad_between = (_MAD_TO_STD * float(np.median(np.abs(d))) for d in (at, between))
    if not mad_at > TICK_ROUGHNESS * mad_between:
        return 0.0
    # mean squares robust to the odd glitch: each row's difference clipped at 10 MADs
    at, between = np.clip(at, -10 * mad_at, 10 * mad_at), np.clip(between, -10 * mad_at, 10 * mad_at)
    return math.sqrt(max(float(np.mean(at**2) - np.mean(between**2)), 0.0) / 2.0)


def estimate(problem) -> NoiseFloor:
    """Model-free estimate of the measurement noise std [N] (see the module docstring)."""
    F = problem.measured
    q = quantum(F)
    smooth = difference_sigma(F, orderings(problem))
    floor, method, rows = math.nan, "differences", 0
    for keys, nuisance in replicate_keys(problem):
        sigma, rows = _replicate_sigma(F, keys, nuisance)
        if not math.isfinite(sigma):
            continue
        if nuisance is None:
            floor, method = sigma, "replicates"  # true repeats: they are the noise
        elif not sigma >= smooth:
            # a two-way layout is exact only for an additive nuisance; otherwise it
            # is one more estimate that is too high, never too low
            floor, method = sigma, "replicates (dwell as a factor)"
        break
    if not math.isfinite(floor):
        floor = smooth
        fitted = smooth_sigma(problem)
        if fitted < floor:
            floor, method = fitted, "smooth fit"
    carried = carried_from_x(problem)
    if carried > floor:
        floor, method = carried, "carried from x"
    if q > 0 and not floor >= q / math.sqrt(12):
        floor, method = q / math.sqrt(12), "quantisation"
    if not floor > 0:
        # noise-free, unquantised data: the finest resolution the column shows
        steps = np.diff(np.unique(F))
        steps = steps[steps > 0]
        floor = float(np.min(steps)) / math.sqrt(12) if steps.size else 0.0
        method = "quantisation"
    return NoiseFloor(floor, method, q, smooth, rows)


def noise_floor(problem) -> float:
    """The model-free noise floor [N] of :func:`estimate`."""
    return estimate(problem).value


def turn_share(values) -> float:
    """Share of the nonzero changes of a column that turn against the previous nonzero
    change: about 1/2 to 2/3 for noise of any size against the column's steps, near 0
    for a programmed ramp, a sine or a held setpoint (it turns only at its extremes);
    NaN with fewer than :data:`MIN_CHANGES` changes."""
    steps = np.diff(np.asanyarray(values, dtype=float))
    signs = np.sign(steps[steps != 0])
    if signs.size < MIN_CHANGES:
        return math.nan
    return float(np.mean(signs[1:] != signs[:-1]))


def computed_from_x(t, x, F) -> float:
    """How much of the force's fast part a linear filter of the position's fast part
    over the last :data:`CONTROLLER_LAGS` samples explains (R², 0 … 1): 1 for a
    controller's output computed from the encoder it reads (its P and D terms turn
    each count into a kick), far below for a measured force, whose sensor's noise no
    position explains. The fast parts are what a local quadratic over
    :data:`FAST_WINDOW` samples leaves."""
    t, x, F = (np.asanyarray(a, dtype=float) for a in (t, x, F))
    n = x.size
    if n < 10 * CONTROLLER_LAGS:
        return 0.0
    x_fast = x - smooth_fit(t, x, FAST_WINDOW)[0]
    F_fast = (F - smooth_fit(t, F, FAST_WINDOW)[0])[CONTROLLER_LAGS:]
    # column k is x_fast delayed by k samples (a view, not a copy)
    lagged = np.lib.stride_tricks.sliding_window_view(x_fast[1:], CONTROLLER_LAGS)[:, ::-1]
    spread = float(np.var(F_fast))
    if not spread > 0:
        return 0.0
    # the normal equations: 16 columns against a million rows, where an SVD of the tall
    # matrix took a second; lstsq on the small system keeps a rank-deficient one (exact
    # x has no fast part) solvable
    coef, *_ = np.linalg.lstsq(lagged.T @ lagged, lagged.T @ F_fast, rcond=None)
    return float(1.0 - np.var(F_fast - lagged @ coef) / spread)


def programmed_force(problem, noise: NoiseFloor) -> bool:
    """Whether the force column is a programme's or a controller's output, not a
    measurement (see :func:`is_command`): such a force has no glitches, and a
    sharp change in it is what was commanded."""
    if problem.kind == "breakaway" or noise.method == "replicates":
        return False
    e_F = noise.smooth_F
    resolution = max(printed_unit(problem.measured), noise.quantum_F)
    turns = turn_share(problem.measured)
    if turns < SMOOTH_TURNS:
        # its changes (nearly) never turn: a programme, less a model of x's at most (a
        # ramp less a gravity model); a sensor's noise turns them half of the time, and
        # noise too small to turn them is too small to matter
        return True
    if math.isfinite(e_F) and e_F <= resolution and turns < COMMAND_TURNS:
        return True
    return problem.kind == "timeseries" and computed_from_x(
        problem.t, problem.recorded_x, problem.measured) >= CONTROLLER_R2


def is_command(problem, noise: NoiseFloor, residual, programmed: bool | None = None) -> bool:
    """Whether the force column is a noise-free command (the measurement noise sits
    in x).

    The force is a command when it carries no noise above its own resolution: its
    differences estimate is at most its last printed digit or its steps, and it turns
    (goes up, then down) only where the programme does (:func:`turn_share` below
    :data:`COMMAND_TURNS`): a programmed ramp, a setpoint held by a PLC, a DAC's steps.
    Or it is a controller's output, computed from the position it reads
    (:func:`computed_from_x` at least :data:`CONTROLLER_R2`). Or its differences are
    far smaller than the base model's ``residual``'s, or negligible against the force
    scale. ``programmed`` is :func:`programmed_force`'s answer where the caller has it
    for the same ``problem`` and ``noise`` (it takes half a second on a million rows).
    """
    if problem.kind == "breakaway" or noise.method == "replicates":
        return False
    e_F = noise.smooth_F
    e_r = difference_sigma(residual, orderings(problem))
    if not (math.isfinite(e_F) and math.isfinite(e_r)):
        return False
    quiet = e_r > 0 and (e_F < COMMAND_RATIO * e_r or e_F < COMMAND_RELATIVE * problem.scales.force)
    if programmed is None:
        programmed = programmed_force(problem, noise)
    return bool(quiet or programmed)


__all__ = ["NoiseFloor", "carried_from_x", "computed_from_x", "difference_sigma", "estimate",
           "is_command", "noise_floor", "orderings", "programmed_force", "smooth_sigma",
           "turn_share"]
