"""The physics behind the machine-like recordings of :mod:`tests.identify.machines`:
a body under a force (a torque command, a spring pulled by a drive) with presliding
friction and reversal memory, and what a real recording does to it afterwards (an
encoder's counts, a DAC's steps, printed decimals).

The plant is ``m·ẍ = u − F``. F follows the reversal-memory law of MODEL.md §3
(E6'), ``F = F_r + (d·g(v) + σ·v − F_r)·f(s·|x − x_r|)``, with g of (E2) per direction
(so an asymmetric axis is one call), an optional viscous σ (a geared joint's oil) and
one of two presliding shapes:

- ``SHAPE_E4``: the note's f(z) = z·(1 − ln z) (:func:`breakaway.presliding.shape_scalar`),
  made linear below z = :data:`E4_LINEAR_BELOW` so that the stiffness after a reversal
  is finite and a fixed step can integrate it (the force differs from E4 there by less
  than 1e-3 of the branch: far below any sensor's noise);
- ``SHAPE_EXPONENTIAL``: a Dahl-like f(z) = 1 − exp(−3z), outside the library (finite
  initial stiffness, no end of presliding at z = 1): what a servo's elastic drive
  train shows and E4 cannot.

Presliding is damped: ``c·v·(1 − f)`` adds to the friction while the contact is in
presliding and vanishes in gross sliding (LuGre's σ1·ż), critically damped on the
stiffest branch (:func:`friction_params`). Without it a branch rings into a reversal,
each reversal starts a new branch (MODEL.md §3) and the record leaves the law it is
meant to follow, and the velocity weakening of g inside a branch pumps a chatter that
never settles (MODEL.md §5). It is outside the library: where a body creeps through
presliding it adds a few per cent of Fc to the force. A reversal (ẋ changes sign)
starts a new branch at the current x and the elastic part of F (MODEL.md §5).
The step is semi-implicit Euler, many sub-steps per recorded sample (the tests check
it against a free body and, quasi-statically, against the core's (E6')).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from breakaway.presliding import shape_scalar

SHAPE_E4, SHAPE_EXPONENTIAL = 0, 1
#: The E4 shape is continued linearly below this z (finite stiffness after a reversal).
E4_LINEAR_BELOW = 1e-4

# the friction parameter vector
P_FC, P_FS, P_FC_NEG, P_FS_NEG, P_V, P_DELTA, P_S, P_SHAPE, P_DAMPING, P_SIGMA, P_ZETA = range(11)
# the state vector: position, velocity, x_r, F_r, direction, last friction
S_X, S_V, S_XR, S_FR, S_D, S_F = range(6)


def friction_params(Fc, Fs, V, delta, s, mass, shape=SHAPE_E4, Fc_neg=None, Fs_neg=None,
                    sigma=0.0, damping_ratio=1.0):
    """The parameter vector of :func:`advance` (levels per direction, the viscous
    coefficient ``sigma``; SI or rotary).

    The presliding damping is critical for the mass on the stiffest branch: one that
    starts at a reversal from one level to the other, ``2·Fs·s`` times the shape's
    slope at its start. A reversal inside a branch then never rings into another
    reversal (each would start a new branch, MODEL.md §3, and move the record off the
    law it is meant to follow). A ``damping_ratio`` below 1 keeps the damping force (a
    term outside the library) small where a fast body crosses presliding, at the cost
    of ringing reversals far below an encoder's count; the sub-steps stay those of the
    critical damping.
    """
    Fc_neg = Fc if Fc_neg is None else Fc_neg
    Fs_neg = Fs if Fs_neg is None else Fs_neg
    slope = 3.0 if shape == SHAPE_EXPONENTIAL else 1.0 - math.log(E4_LINEAR_BELOW)
    damping = 2.0 * math.sqrt(2.0 * max(Fs, Fs_neg) * s * slope * mass)
    return np.array([Fc, Fs, Fc_neg, Fs_neg, V, delta, s, shape, damping, sigma, damping_ratio],
                    dtype=float)


def rest_state():
    """At rest at x = 0 in the virgin state (x_r = 0, F_r = 0, d = +1)."""
    return np.array([0.0, 0.0, 0.0, 0.0, 1.0, 0.0])


@njit(cache=True)
def _shape(z, kind):
    if kind == SHAPE_EXPONENTIAL:
        return 1.0 - math.exp(-3.0 * z)
    if z < E4_LINEAR_BELOW:
        return z * (1.0 - math.log(E4_LINEAR_BELOW))
    return shape_scalar(z)


@njit(cache=True)
def friction(state, p):
    """The friction force [N]: (E6') on the current branch plus the presliding damping."""
    z = p[P_S] * abs(state[S_X] - state[S_XR])
    shape = _shape(z, int(p[P_SHAPE]))
    return elastic(state, p, shape) + p[P_DAMPING] * p[P_ZETA] * state[S_V] * (1.0 - shape)


@njit(cache=True)
def elastic(state, p, shape):
    """(E6') at the state with the branch's shape value f(z) (σ·v inside the target)."""
    d = state[S_D]
    v = state[S_V]
    if d > 0:
        Fc, Fs = p[P_FC], p[P_FS]
    else:
        Fc, Fs = p[P_FC_NEG], p[P_FS_NEG]
    g = Fc + (Fs - Fc) * math.exp(-(abs(v) / p[P_V]) ** p[P_DELTA])
    return state[S_FR] + (d * g + p[P_SIGMA] * v - state[S_FR]) * shape


@njit(cache=True)
def advance(state, p, m, force, drive0, drive1, stiffness, duration, substeps):
    """Advance ``state`` in place over one recorded sample of ``duration`` [s].

    The applied force is ``force`` (held over the sample: a command's zero-order hold)
    plus ``stiffness·(drive − x)``, a spring whose far end moves linearly from
    ``drive0`` to ``drive1`` over the sample (0 stiffness: no spring).
    """
    h = duration / substeps
    for j in range(substeps):
        drive = drive0 + (drive1 - drive0) * (j + 0.5) / substeps
        F = friction(state, p)
        u = force + stiffness * (drive - state[S_X])
        v = state[S_V] + h * (u - F) / m
        if v * state[S_D] < 0.0:
            # a reversal: a new branch from the current position and elastic force
            z = p[P_S] * abs(state[S_X] - state[S_XR])
            state[S_FR] = elastic(state, p, _shape(z, int(p[P_SHAPE])))
            state[S_XR] = state[S_X]
            state[S_D] = -state[S_D]
        state[S_V] = v
        state[S_X] += h * v
    state[S_F] = friction(state, p)


def substeps_for(p, m, duration, at_least=1):
    """Sub-steps of a sample of ``duration`` [s] that keep the explicit step stable on
    the stiffest, critically damped presliding branch, and under the viscous drag:
    h·c/m ≤ 0.4 (h·ω0 ≤ 0.2)."""
    damping = max(p[P_DAMPING], p[P_SIGMA])
    return max(int(at_least), math.ceil(duration * damping / (0.4 * m)))


def run_open_loop(t, force, p, m, substeps, drive=None, stiffness=0.0):
    """The plant under a recorded force sequence (and a spring to a drive position),
    with at least ``substeps`` sub-steps per sample (more where stability needs them).

    Returns
    -------
    x, v, friction : numpy.ndarray
        At each sample time [m, m/s, N] (rotary: rad, rad/s, N·m).
    """
    n = t.size
    drive = np.zeros(n) if drive is None else drive
    out = np.empty((3, n))
    state = rest_state()
    substeps = substeps_for(p, m, float(np.max(np.diff(t))), substeps)
    return _run(t, np.asarray(force, float), np.asarray(drive, float), p, m, stiffness,
                substeps, state, out)


@njit(cache=True)
def _run(t, force, drive, p, m, stiffness, substeps, state, out):
    n = t.size
    out[0, 0], out[1, 0], out[2, 0] = state[S_X], state[S_V], friction(state, p)
    for i in range(1, n):
        advance(state, p, m, force[i - 1], drive[i - 1], drive[i], stiffness,
                t[i] - t[i - 1], substeps)
        out[0, i], out[1, i], out[2, i] = state[S_X], state[S_V], state[S_F]
    return out[0], out[1], out[2]


# ---------------------------------------------------------------------------------
# what a recording does
# ---------------------------------------------------------------------------------


def encoder_counts(x, count, rng, at_rest=None, share=0.3):
    """An incremental encoder's reading: whole counts of ``count`` below the true
    position, the grid at a random phase (where the index pulse happened to be).

    Where ``at_rest``, a ``share`` of the samples read the neighbouring count across
    the nearer edge of the grating: the flicker of an encoder standing on an edge.
    """
    scaled = (np.asarray(x, float) + rng.random() * count) / count
    counts = np.floor(scaled)
    if at_rest is not None:
        nearer = np.where(scaled - counts >= 0.5, 1.0, -1.0)
        counts += np.where(at_rest & (rng.random(counts.size) < share), nearer, 0.0)
    return counts


def quantise(values, step):
    """A DAC's or ADC's steps: ``values`` rounded to whole ``step``."""
    return np.round(np.asarray(values, float) / step) * step


def csv_text(columns, meta=None, comments=()):
    """CSV text as a logger writes it: ``# key: value`` lines, a header, and each
    column printed with its own format (the printed rounding is part of the record).

    ``columns`` maps header names to ``(values, format)`` pairs, e.g. ``"%.4f"``.
    """
    lines = [f"# {c}" for c in comments]
    lines += [f"# {key}: {value}" for key, value in (meta or {}).items()]
    names = list(columns)
    lines.append(",".join(names))
    formats = [columns[c][1] for c in names]
    table = np.column_stack([np.asarray(columns[c][0], float) for c in names])
    row = ",".join(formats)
    lines.extend(row % tuple(values) for values in table)
    return "\n".join(lines) + "\n"
