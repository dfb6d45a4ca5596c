"""Steady-state Stribeck curve (E2)."""

import math

import numpy as np
import pytest

from breakaway.steady import steady_state_force, stribeck_magnitude

NAN = float("nan")
P = dict(Fc=1.0, Fs=1.5, V=2.0, delta=1.0)


def g_hand(v, Fc, Fs, V, delta):
    """(E2) written out with the math module, the limits of MODEL.md §2 at v = 0."""
    if v == 0:
        return Fs if delta > 0 else Fc
    return Fc + (Fs - Fc) * math.exp(-((abs(v) / V) ** delta))


@pytest.mark.parametrize("delta", [0.5, 1.0, 2.0, 7.0, -0.5, -1.0, -3.0])
@pytest.mark.parametrize("v", [0.0, 1e-6, 0.3, 2.0, -2.0, 5.0, -40.0])
def test_magnitude_against_hand_formula(v, delta):
    expected = g_hand(v, 1.0, 1.5, 2.0, delta)
    assert stribeck_magnitude(v, 1.0, 1.5, 2.0, delta) == pytest.approx(expected, rel=1e-14)


def test_magnitude_known_values():
    # g(V) = Fc + (Fs − Fc)/e for every δ
    for delta in (0.5, 1.0, 2.0, -1.0):
        assert stribeck_magnitude(2.0, 1.0, 1.5, 2.0, delta) == pytest.approx(
            1.0 + 0.5 / math.e, rel=1e-15)
    assert stribeck_magnitude(0.0, **P) == 1.5  # δ > 0: g(0) = Fs
    assert stribeck_magnitude(0.0, 1.0, 1.5, 2.0, -1.0) == 1.0  # δ < 0: g(0) = Fc


def test_magnitude_limits_at_large_speed():
    assert stribeck_magnitude(1e6, **P) == pytest.approx(1.0, abs=1e-15)  # → Fc
    assert stribeck_magnitude(1e6, 1.0, 1.5, 2.0, -1.0) == pytest.approx(1.5, abs=1e-5)  # → Fs


@pytest.mark.parametrize("delta, rising", [(1.0, False), (2.0, False), (-1.0, True)])
def test_magnitude_is_monotone_in_speed_and_bounded(delta, rising):
    v = np.linspace(0.0, 50.0, 2001)
    g = stribeck_magnitude(v, 1.0, 1.5, 2.0, delta)
    steps = np.diff(g)
    assert np.all(steps >= 0) if rising else np.all(steps <= 0)
    assert np.all((g >= 1.0) & (g <= 1.5))


def test_magnitude_is_even_and_keeps_shape():
    v = np.linspace(-3, 3, 12).reshape(3, 4)
    g = stribeck_magnitude(v, **P)
    assert g.shape == (3, 4)
    np.testing.assert_array_equal(g, stribeck_magnitude(-v, **P))


def test_steady_force_is_odd_with_viscous_term():
    v = np.linspace(-10, 10, 401)
    F = steady_state_force(v, 1.0, 1.5, 2.0, 1.0, sigma=0.2)
    np.testing.assert_allclose(F, -steady_state_force(-v, 1.0, 1.5, 2.0, 1.0, sigma=0.2),
                               rtol=0, atol=1e-15)
    np.testing.assert_allclose(F - np.sign(v) * stribeck_magnitude(v, **P), 0.2 * v,
                               rtol=0, atol=1e-14)


def test_steady_force_values():
    assert steady_state_force(0.0, **P, sigma=0.3) == 0.0  # sgn(0) = 0
    assert steady_state_force(2.0, **P, sigma=0.3) == pytest.approx(1 + 0.5 / math.e + 0.6,
                                                                     rel=1e-15)
    assert steady_state_force(-4.0, **P) == pytest.approx(-(1 + 0.5 * math.exp(-2)), rel=1e-15)


def test_no_stribeck_dip_when_levels_are_equal():
    v = np.linspace(-5, 5, 11)
    np.testing.assert_allclose(steady_state_force(v, 1.0, 1.0, 2.0, 1.0),
                               np.sign(v), rtol=0, atol=0)


@pytest.mark.parametrize("func", [stribeck_magnitude, steady_state_force])
@pytest.mark.parametrize(
    "bad, name",
    [(dict(Fs=0.5), "Fs"), (dict(V=0.0), "V"), (dict(V=-1.0), "V"), (dict(delta=0.0), "delta"),
     (dict(Fc=NAN), "Fc"), (dict(Fs=NAN), "Fs"), (dict(V=NAN), "V"), (dict(delta=NAN), "delta"),
     (dict(Fc=0.0), "Fc")],
)
def test_bad_parameters_raise_naming_them(func, bad, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        func(1.0, **{**P, **bad})


def test_bad_sigma_raises():
    with pytest.raises(ValueError, match=r"^sigma must"):
        steady_state_force(1.0, **P, sigma=-1.0)
    with pytest.raises(ValueError, match=r"^sigma must"):
        steady_state_force(1.0, **P, sigma=NAN)
