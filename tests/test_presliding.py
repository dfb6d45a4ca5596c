"""Presliding shape (E4) and the reversal-memory law (E6') along sampled trajectories."""

import math

import numpy as np
import pytest

from breakaway.presliding import (
    LOOP_TURNING_POINTS,
    hysteresis_loop,
    motion_direction,
    presliding_force,
    presliding_force_from_target,
    presliding_shape,
    presliding_slope,
)
from breakaway.steady import steady_state_force, stribeck_magnitude

NAN = float("nan")
P = dict(Fc=1.0, Fs=1.5, V=2.0, delta=1.0)


def sine_run(amplitude, periods=4, per_period=400, s=1.0):
    """x = amplitude·sin(2πt)/s sampled ``per_period`` times per period (even)."""
    t = np.arange(periods * per_period + 1) / per_period
    return t, amplitude / s * np.sin(2 * np.pi * t)


# ---------------------------------------------------------------------------------
# the shape f(z) (E4)
# ---------------------------------------------------------------------------------


def test_shape_endpoints_and_slope_at_one():
    assert presliding_shape(0.0) == 0.0
    assert presliding_shape(1.0) == 1.0
    assert presliding_slope(1.0) == 0.0
    assert presliding_slope(0.0) == np.inf
    # saturated beyond the presliding distance
    np.testing.assert_array_equal(presliding_shape([1.0, 1.5, 40.0]), [1.0, 1.0, 1.0])
    np.testing.assert_array_equal(presliding_slope([1.5, 40.0]), [0.0, 0.0])


@pytest.mark.parametrize("z", [1e-12, 1e-3, 0.1, 0.5, 0.9, 0.95, 0.999])
def test_shape_and_slope_against_hand_formula(z):
    assert presliding_shape(z) == pytest.approx(z * (1 - math.log(z)), rel=1e-15)
    assert presliding_slope(z) == pytest.approx(-math.log(z), rel=1e-15)
    # f' is the derivative of f (central difference)
    h = 1e-7 * z
    numeric = (z + h) * (1 - math.log(z + h)) - (z - h) * (1 - math.log(z - h))
    assert presliding_slope(z) == pytest.approx(numeric / (2 * h), rel=1e-6, abs=1e-9)


def test_shape_at_break_away_fraction():
    assert presliding_shape(0.95) == pytest.approx(0.95 * (1 - math.log(0.95)), rel=1e-15)
    assert presliding_shape(0.95) == pytest.approx(0.9987286297, rel=1e-10)


def test_shape_is_increasing_concave_and_below_one():
    z = np.linspace(0, 1, 10001)
    f = presliding_shape(z)
    assert np.all(np.diff(f) > 0)
    assert np.all(np.diff(f, 2) < 0)
    assert np.all((f >= z) & (f <= 1))


def test_shape_rejects_negative_z():
    with pytest.raises(ValueError, match="z"):
        presliding_shape([0.1, -0.1])
    with pytest.raises(ValueError, match="z"):
        presliding_slope(-1e-9)


# ---------------------------------------------------------------------------------
# motion direction
# ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "x, d",
    [
        ([0, 1, 1, 0.5, 0.5, 2], [1, 1, 1, -1, -1, 1]),
        ([3, 3, 2, 2, 4], [-1, -1, -1, -1, 1]),  # d_0 from the first non-zero increment
        ([1, 1, 1], [1, 1, 1]),  # no motion: +1
        ([0], [1]),
        ([0, -1, -2, -1], [-1, -1, -1, 1]),
    ],
)
def test_motion_direction(x, d):
    np.testing.assert_array_equal(motion_direction(x), d)


# ---------------------------------------------------------------------------------
# (E6') along a sampled trajectory
# ---------------------------------------------------------------------------------


def e6_hand(t, x, Fc, Fs, V, delta, s, sigma=0.0, F0=0.0):
    """MODEL.md §3 reference discretisation written out sample by sample."""
    n = len(x)
    v = [(x[1] - x[0]) / (t[1] - t[0])]
    v += [(x[i + 1] - x[i - 1]) / (t[i + 1] - t[i - 1]) for i in range(1, n - 1)]
    v += [(x[-1] - x[-2]) / (t[-1] - t[-2])]  # uniform t: numpy.gradient's formula
    steps = [x[i] - x[i - 1] for i in range(1, n)]
    first = next((st for st in steps if st != 0), 1.0)
    d = [math.copysign(1.0, first)]
    for st in steps:
        d.append(math.copysign(1.0, st) if st != 0 else d[-1])
    x_r, F_r, F = x[0], F0, []
    for i in range(n):
        if i > 0 and d[i] != d[i - 1]:
            x_r, F_r = x[i - 1], F[i - 1]
        z = min(s * abs(x[i] - x_r), 1.0)
        shape = z * (1 - math.log(z)) if z > 0 else 0.0
        av = abs(v[i])
        g = (Fs if delta > 0 else Fc) if av == 0 else Fc + (Fs - Fc) * math.exp(-(av / V) ** delta)
        F.append(F_r + (d[i] * g + sigma * v[i] - F_r) * shape)
    return np.array(F)


SHORT_T = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0]
SHORT_X = [0.0, 0.2, 0.5, 0.3, 0.1, 0.4, 1.6]


def test_e6_against_hand_computation_on_a_short_trajectory():
    F = presliding_force(SHORT_T, SHORT_X, **P, s=1.0, sigma=0.1)
    np.testing.assert_allclose(F, e6_hand(SHORT_T, SHORT_X, **P, s=1.0, sigma=0.1),
                               rtol=1e-13, atol=1e-15)
    # sample 1 by hand: v = 0.25, z = 0.2, g = 1 + 0.5·e^(−1/8), F = (g + 0.025)·f(0.2)
    f02 = 0.2 * (1 + math.log(5))
    assert F[1] == pytest.approx((1 + 0.5 * math.exp(-0.125) + 0.025) * f02, rel=1e-14)
    # sample 3 reverses: the branch starts at (x_2, F_2) and heads for −g(v_3) + σ·v_3
    v3 = (0.1 - 0.5) / 2
    f3 = 0.2 * (1 + math.log(5))
    target3 = -(1 + 0.5 * math.exp(-abs(v3) / 2)) + 0.1 * v3
    assert F[3] == pytest.approx(F[2] + (target3 - F[2]) * f3, rel=1e-14)
    # sample 6 is 1.5/s past the reversal at x_4 = 0.1: gross sliding, F = Fss(v_6)
    assert F[6] == pytest.approx(1 + 0.5 * math.exp(-0.6) + 0.12, rel=1e-14)


def test_initial_force_F0_is_the_first_branch_memory():
    F = presliding_force(SHORT_T, SHORT_X, **P, s=1.0, F0=-0.7)
    np.testing.assert_allclose(F, e6_hand(SHORT_T, SHORT_X, **P, s=1.0, F0=-0.7),
                               rtol=1e-13, atol=1e-15)
    assert F[0] == -0.7


@pytest.mark.parametrize("seed", [0, 1, 2])
@pytest.mark.parametrize("s", [1.0, 250.0])
def test_e6_against_hand_computation_on_random_walks(seed, s):
    rng = np.random.default_rng(seed)
    t = np.arange(300) * 0.01
    x = np.cumsum(rng.normal(0, 0.08, 300)) / s
    x[50:53] = x[49]  # a standstill keeps the direction
    F = presliding_force(t, x, 1.0, 1.6, 3.0, 2.0, s, sigma=0.05)
    np.testing.assert_allclose(F, e6_hand(t, x, 1.0, 1.6, 3.0, 2.0, s, sigma=0.05),
                               rtol=1e-12, atol=1e-13)


def test_from_target_is_the_same_law():
    t, x = np.asarray(SHORT_T), np.asarray(SHORT_X)
    v = np.gradient(x, t)
    target = motion_direction(x) * stribeck_magnitude(v, **P) + 0.1 * v
    np.testing.assert_array_equal(presliding_force_from_target(x, target, 1.0),
                                  presliding_force(t, x, **P, s=1.0, sigma=0.1))


@pytest.mark.parametrize("per_period", [100, 1000, 10000])
def test_force_is_continuous_at_every_reversal(per_period):
    t, x = sine_run(0.3, periods=3, per_period=per_period)
    F = presliding_force(t, x, **P, s=1.0)
    d = motion_direction(x)
    reversals = np.flatnonzero(d[1:] != d[:-1]) + 1
    assert reversals.size == 6
    jump = np.abs(F[reversals] - F[reversals - 1])
    dx = np.abs(x[reversals] - x[reversals - 1])
    # the first step of a new branch moves F by |target − F_r|·f(s·Δx) <= 2·Fs·f(s·Δx)
    assert np.all(jump <= 2 * 1.5 * presliding_shape(dx) + 1e-15)
    # ... which vanishes as the sampling is refined: no jump of the order of F
    assert jump.max() < {100: 0.05, 1000: 2e-3, 10000: 5e-5}[per_period]


def test_gross_sliding_gives_the_steady_state_force():
    t = np.linspace(0.0, 4.0, 801)
    x = 0.3 * t + 0.2 * t**2  # monotone, far beyond the presliding distance 1/s
    for sigma in (0.0, 0.2):
        F = presliding_force(t, x, **P, s=2.0, sigma=sigma)
        v = np.gradient(x, t)
        sliding = 2.0 * x >= 1.0
        assert sliding.sum() == 601  # t >= 1
        np.testing.assert_allclose(F[sliding], steady_state_force(v[sliding], **P, sigma=sigma),
                                   rtol=1e-12, atol=0)
        assert np.all(np.abs(F[~sliding]) < np.abs(steady_state_force(v[~sliding], **P,
                                                                        sigma=sigma)) + 1e-15)


def test_odd_symmetry_under_x_to_minus_x():
    rng = np.random.default_rng(7)
    t = np.arange(400) * 0.01
    x = np.cumsum(rng.normal(0, 0.1, 400))
    F = presliding_force(t, x, **P, s=1.3, sigma=0.1, F0=0.4)
    F_mirror = presliding_force(t, -x, **P, s=1.3, sigma=0.1, F0=-0.4)
    np.testing.assert_allclose(F_mirror, -F, rtol=0, atol=1e-15)


@pytest.mark.parametrize("amplitude", [0.6, 1.0, 1.5])
def test_major_loop_closes_and_is_odd_when_the_swing_exceeds_the_presliding_distance(amplitude):
    # reversal to reversal the motion covers 2·amplitude/s >= 1/s: memory is wiped
    n = 400
    t, x = sine_run(amplitude, periods=4, per_period=n, s=2.0)
    F = presliding_force(t, x, **P, s=2.0)
    cycle2, cycle3 = F[n:2 * n], F[2 * n:3 * n]
    np.testing.assert_allclose(cycle3, cycle2, rtol=0, atol=1e-12)
    # descending half = − ascending half: F(−x) = −F(x) along the loop
    np.testing.assert_allclose(F[n + n // 2:2 * n], -F[n:n + n // 2], rtol=0, atol=1e-12)
    assert np.max(np.abs(F)) <= 1.5 + 1e-15


@pytest.mark.parametrize("amplitude", [0.2, 0.4])
def test_small_loops_have_local_memory_only(amplitude):
    """Below the presliding distance only the last reversal is kept: the loop does not
    close after one cycle but drifts geometrically onto a symmetric limit loop."""
    n = 400
    t, x = sine_run(amplitude, periods=12, per_period=n)
    F = presliding_force(t, x, **P, s=1.0)
    drift = [np.max(np.abs(F[(c + 1) * n:(c + 2) * n] - F[c * n:(c + 1) * n]))
             for c in range(11)]
    assert drift[1] > 1e-4  # cycle 3 differs from cycle 2: not closed
    assert drift[2] < 0.1 * drift[1]
    assert drift[-1] < 1e-9
    last = F[11 * n:12 * n + 1]
    np.testing.assert_allclose(last[n // 2:], -last[:n // 2 + 1], rtol=0, atol=1e-9)


# ---------------------------------------------------------------------------------
# hysteresis_loop (the explorer's Fig. 1)
# ---------------------------------------------------------------------------------


def test_default_loop_shape_and_bounds():
    x, F = hysteresis_loop(**P, s=2.0)
    assert x.shape == F.shape == (2000,)
    assert x.max() == pytest.approx(1.5 / 2.0, rel=1e-5)
    assert x.min() == pytest.approx(-1.5 / 2.0, rel=1e-5)
    assert F[0] == 0.0
    assert np.max(np.abs(F)) <= 1.5 + 1e-15
    # amplitude 1.5/s: the major loop reaches gross sliding at g(v) near its turning points
    assert F.max() > 1.45 and F.min() < -1.45


def test_loop_is_odd_under_mirrored_excitation():
    tp = np.asarray(LOOP_TURNING_POINTS)
    x, F = hysteresis_loop(**P, s=1.0, sigma=0.05, amplitude=0.8, turning_points=tp)
    xm, Fm = hysteresis_loop(**P, s=1.0, sigma=0.05, amplitude=0.8, turning_points=-tp)
    np.testing.assert_allclose(xm, -x, rtol=0, atol=1e-15)
    np.testing.assert_allclose(Fm, -F, rtol=0, atol=1e-15)


def test_minor_loop_lies_inside_the_major_loop():
    x, F = hysteresis_loop(**P, s=1.0, amplitude=1.5, n=4000)
    seg = np.linspace(0.0, len(LOOP_TURNING_POINTS) - 1, 4000).astype(int)
    up, down = seg == 3 - 1, seg == 3  # third segment −A → A, fourth A → 0.2A
    minor = (seg == 4) | (seg == 5)  # 0.2A → 0.6A → 0.2A
    lo = np.interp(x[minor], x[down][::-1], F[down][::-1])
    hi = np.interp(x[minor], x[up], F[up])
    assert np.all(F[minor] >= lo - 1e-9) and np.all(F[minor] <= hi + 1e-9)
    assert np.ptp(F[minor]) > 0.1  # a real loop, not a line


@pytest.mark.parametrize(
    "bad, name",
    [(dict(Fs=0.5), "Fs"), (dict(V=0.0), "V"), (dict(delta=0.0), "delta"),
     (dict(Fc=NAN), "Fc"), (dict(s=0.0), "s"), (dict(s=NAN), "s"), (dict(sigma=-1.0), "sigma")],
)
def test_presliding_force_bad_parameters(bad, name):
    kwargs = {**P, "s": 1.0, **bad}
    with pytest.raises(ValueError, match=rf"^{name} must"):
        presliding_force(SHORT_T, SHORT_X, **kwargs)
    with pytest.raises(ValueError, match=rf"^{name} must"):
        hysteresis_loop(**kwargs)


def test_bad_initial_force_and_scale_raise():
    with pytest.raises(ValueError, match=r"^F0 must"):
        presliding_force(SHORT_T, SHORT_X, **P, s=1.0, F0=NAN)
    with pytest.raises(ValueError, match=r"^s must"):
        presliding_force_from_target(SHORT_X, np.ones(7), s=-1.0)
    with pytest.raises(ValueError, match=r"^s must"):
        presliding_force_from_target(SHORT_X, np.ones(7), s=NAN)
    with pytest.raises(ValueError, match=r"^F0 must"):
        presliding_force_from_target(SHORT_X, np.ones(7), s=1.0, F0=NAN)


@pytest.mark.parametrize("bad, name", [(dict(amplitude=0.0), "amplitude"),
                                       (dict(amplitude=NAN), "amplitude"),
                                       (dict(peak_speed=-1.0), "peak_speed"),
                                       (dict(n=5), "n")])
def test_hysteresis_loop_bad_options(bad, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        hysteresis_loop(**P, s=1.0, **bad)
