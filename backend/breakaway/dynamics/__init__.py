"""Dynamic simulation of the ramp experiment (E7), of the LuGre comparison model, and
of either in a position loop.

All models are written with one signature (python-control's ``nlsys`` idea) and
integrated in one place, :func:`breakaway.dynamics.integrator._integrate`:

- ``rhs(t, y, p, mem, dy)`` writes the state derivative ``dy``;
- ``force(t, y, p, mem)`` returns the friction force F [N];
- ``guard(t, y, p, mem)``: a sign change from ``>= 0`` to ``< 0`` calls
  ``jump(t, y, p, mem)``, which updates the discrete memory ``mem`` in place
  (a motion reversal starting a new presliding branch; in the loop also a
  break-away or the compensation's branch) and returns the event's code;
- ``stop(t, y, p, mem)``: a change from ``< 0`` to ``>= 0`` ends the run
  (the ramp's break-away; a loop that runs away).

``p`` holds the parameters (the rate ``k``, or the controller and reference) and
``mem`` the discrete state.
The integrator is an adaptive Dormand–Prince 5(4) scheme compiled with numba. Each
accepted step's cubic Hermite interpolant is scanned for events, which are then located
by bisection, so a short excursion inside one step is not missed, and the step restarts
exactly at a reversal (a change of sign of ẋ starts a new branch at the current x and
F). The models are selected by id inside compiled code (:mod:`.table`)
because numba cannot cache functions that receive jitted functions as arguments.

With velocity weakening the quasi-static branch of (E12) is unstable: the body chatters
through many reversals before it breaks away, and at small rates the break-away
becomes sensitive to round-off (a chaotic transient). There the result is defined only
to the scatter between tolerances, which the tests and the benchmark measure.
Modules: :mod:`.ramp_model` (E7 with E6'), :mod:`.lugre` (LuGre), :mod:`.loop_model`
(the position loop around either), :mod:`.table` (the model table), :mod:`.integrator` (the
compiled scheme, shared by all), :mod:`.runs` (its Python side), :mod:`.common` (g of
E2 compiled, event codes).
"""

from __future__ import annotations

import numpy as np

from ..params import DEFAULTS, check_positive
from .common import EVENT_BREAKAWAY, EVENT_STICK
from .loop_model import _REVERSALS, _loop_outputs, loop_problem
from .lugre import _lugre_problem
from .ramp_model import _presliding_problem
from .runs import (DEFAULT_RTOL, LOOP_LUGRE, LOOP_PRESLIDING, LUGRE, MIN_RTOL, PRESLIDING,
                   LoopRun, RampBreakaway, Trajectory, _check_rtol, _run_grid, _run_one,
                   _run_sweep)

def _rates(k):
    k = np.atleast_1d(np.asanyarray(k, dtype=float)).ravel()
    if k.size == 0 or np.any(~np.isfinite(k)) or np.any(k <= 0):
        raise ValueError("k must be a non-empty list of finite rates > 0")
    return k


def simulate_breakaway(k, Fc, Fs, V, delta, s=1.0, sigma=0.0, m=DEFAULTS["m"], z_ba=0.95,
                       rtol=DEFAULT_RTOL, max_steps=2_000_000):
    """Break-away of the ramp experiment ``m·ẍ + F = k·t`` (E7) for each rate.

    Starts at rest in the virgin presliding state; F follows (E6') with exact reversal
    handling. Break-away is the first time ``s·|x − x_r| >= z*`` with ``d = +1``.

    Parameters
    ----------
    k : array_like
        Actuation force rates [N/s], each > 0.
    Fc, Fs, V, delta, sigma :
        Steady-state parameters (E2), units as in :mod:`breakaway.steady`.
    s : float, optional
        Presliding scale [1/m].
    m : float, optional
        Moving mass [kg].
    z_ba : float, optional
        Presliding fraction taken as break-away [-].
    rtol : float, optional
        Relative tolerance of the adaptive integrator.
    max_steps : int, optional
        Step budget per rate; a rate that exhausts it reports NaN.

    Returns
    -------
    RampBreakaway
        ``u_ba = k·t_ba`` [N], ``F_ba`` [N], ``t_ba`` [s] per rate.
    """
    ks = _rates(k)
    _check_rtol(rtol)
    p, y0, mem0, t_end, atols = _presliding_problem(ks, Fc, Fs, V, delta, s, sigma, m, z_ba,
                                                    rtol)
    return _run_sweep(PRESLIDING, ks, p, y0, mem0, t_end, atols, rtol, max_steps)


def simulate_trajectory(k, Fc, Fs, V, delta, s=1.0, sigma=0.0, m=DEFAULTS["m"], z_ba=0.95,
                        rtol=DEFAULT_RTOL, max_steps=2_000_000, capacity=200_000):
    """One ramp run of (E7) up to break-away, recorded at every step and reversal.

    Parameters are those of :func:`simulate_breakaway` with a single rate ``k`` [N/s];
    ``capacity`` bounds the number of recorded samples.

    Returns
    -------
    Trajectory
    """
    ks = _rates(k)
    if ks.size != 1:
        raise ValueError("k must be a single rate")
    _check_rtol(rtol)
    p, y0, mem0, t_end, atols = _presliding_problem(ks, Fc, Fs, V, delta, s, sigma, m, z_ba,
                                                    rtol)
    return _run_one(PRESLIDING, ks[0], p, y0, mem0, t_end[0], atols[0], rtol, max_steps,
                    capacity)


def simulate_lugre_breakaway(k, params=None, rtol=DEFAULT_RTOL, max_steps=2_000_000):
    """Break-away of the LuGre model under the ramp ``u = k·t``: the first local max of F.

    Parameters
    ----------
    k : array_like
        Actuation force rates [N/s].
    params : dict, optional
        Overrides of :data:`breakaway.params.LUGRE_1995` (``sigma0`` [N/m], ``sigma1``
        [N s/m], ``sigma2`` [N s/m], ``Fc``, ``Fs`` [N], ``vs`` [m/s], ``delta``, ``m`` [kg]).
    rtol : float, optional
        Relative tolerance.

    Returns
    -------
    RampBreakaway
        ``F_ba`` is the first local maximum of F, ``u_ba = k·t`` at that instant.
    """
    ks = _rates(k)
    _check_rtol(rtol)
    p, y0, mem0, t_end, atols = _lugre_problem(ks, params, rtol)
    return _run_sweep(LUGRE, ks, p, y0, mem0, t_end, atols, rtol, max_steps)


def simulate_lugre_trajectory(k, params=None, rtol=DEFAULT_RTOL, max_steps=2_000_000,
                              capacity=200_000):
    """One LuGre ramp run up to the first local maximum of F (see :func:`simulate_lugre_breakaway`)."""
    ks = _rates(k)
    if ks.size != 1:
        raise ValueError("k must be a single rate")
    _check_rtol(rtol)
    p, y0, mem0, t_end, atols = _lugre_problem(ks, params, rtol)
    return _run_one(LUGRE, ks[0], p, y0, mem0, t_end[0], atols[0], rtol, max_steps, capacity)


#: Events a loop run keeps at most beyond its output grid (break-aways and stick starts).
LOOP_EVENT_CAPACITY = 20_000


def simulate_loop(params, controller, reference, duration, compensation=None,
                  model="presliding", points=2000, rtol=DEFAULT_RTOL, max_steps=2_000_000):
    """The position loop: ``m·ẍ + F = u`` under PID control.

    ``u = Kp·e + Ki·∫e dt + Kd·(ṙ − ẋ) + c·F_m(ṙ)``, ``e = r − x``, ``|u| <= u_max``:
    the derivative acts on the velocity error (no kick at a step), and only the output
    is clamped, so the integrator winds up while u sits on its limit (no anti-windup:
    the windup is what the loop view shows). From rest in the virgin presliding state,
    ∫e = 0.

    Parameters
    ----------
    params : dict
        The plant: ``presliding`` takes Fc, Fs [N], V [m/s], delta, sigma [N s/m],
        s [1/m], m [kg], z_ba; ``lugre`` overrides of
        :data:`breakaway.params.LUGRE_1995` and z_ba.
    controller : dict
        Kp [N/m], Ki [N/(m s)], Kd [N s/m], each >= 0, and u_max [N] (> 0, or None).
    reference : dict
        ``kind``: 'step' (height ``h`` [m]), 'ramp' (speed ``w`` [m/s] from rest) or
        'sine' (amplitude ``h`` [m], frequency ``f`` [Hz]).
    duration : float
        Simulated time [s].
    compensation : dict, optional
        ``{"scale": c, "params": {...}}``: F_m = Fss(ṙ) of (E2) with the plant's
        steady state unless ``params`` overrides Fc, Fs, V, delta, sigma; c = 0 (the
        default) is off, 1 exact.
    model : {'presliding', 'lugre'}
    points : int
        Samples of the uniform output grid (>= 2); break-aways and stick-phase starts
        are added at their exact times.
    rtol : float
        Relative tolerance of the integrator.
    max_steps : int
        Step budget; when it runs out the run ends early (``t_end < duration``), as
        it does when the loop runs away (``runaway``).

    Returns
    -------
    LoopRun
    """
    if model not in ("presliding", "lugre"):
        raise ValueError(f"model must be 'presliding' or 'lugre', got {model!r}")
    check_positive(duration=duration)
    if int(points) < 2:
        raise ValueError(f"points must be >= 2, got {points}")
    _check_rtol(rtol)
    compensation = compensation or {"scale": 0.0}
    p, y0, mem0, atol = loop_problem(model, params, controller, reference, compensation,
                                     float(duration), rtol)
    entry = LOOP_LUGRE if model == "lugre" else LOOP_PRESLIDING
    rec, mem = _run_grid(entry.id, p, y0, mem0, float(duration), atol, rtol, max_steps,
                         int(points), EVENT_BREAKAWAY | EVENT_STICK, LOOP_EVENT_CAPACITY)
    r, u = _loop_outputs(rec.t, rec.y, rec.mem, p)
    x = rec.y[:, 0]
    return LoopRun(rec.t, x, rec.y[:, 1], u, rec.F, r, r - x, rec.code, rec.t_end,
                   rec.stopped, int(mem[_REVERSALS]))


__all__ = ["DEFAULT_RTOL", "LoopRun", "MIN_RTOL", "RampBreakaway", "Trajectory",
           "simulate_breakaway", "simulate_loop", "simulate_lugre_breakaway",
           "simulate_lugre_trajectory", "simulate_trajectory"]
