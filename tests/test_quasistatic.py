"""Quasi-static break-away: the phase family (E12) and the break-away curve (E13)."""

import math
import warnings

import numpy as np
import pytest

from breakaway.params import DEFAULTS, F_HAT_CHOICES, FIG3_RATES
from breakaway.quasistatic import (
    breakaway_force,
    breakaway_velocity,
    level,
    phase_family,
    presliding_velocity,
)
from breakaway.steady import steady_state_force

NAN = float("nan")
P = dict(Fc=1.0, Fs=1.5, V=100.0, delta=1.0)  # the default preset's curve
LEVELS = {"Fc": 1.0, "Fs": 1.5, "avg": 1.25}


def test_levels():
    assert level("Fc", 1.0, 1.5) == 1.0
    assert level("Fs", 1.0, 1.5) == 1.5
    assert level("avg", 1.0, 1.5) == 1.25
    assert level("avg", 2.0, 5.0) == 3.5
    with pytest.raises(ValueError, match="self"):
        level("self", 1.0, 1.5)
    with pytest.raises(ValueError, match="F_hat"):
        level("max", 1.0, 1.5)


# ---------------------------------------------------------------------------------
# E12
# ---------------------------------------------------------------------------------


@pytest.mark.parametrize("F_hat", ["Fc", "Fs", "avg"])
@pytest.mark.parametrize("s", [1.0, 1e4])
@pytest.mark.parametrize("k", [0.01, 2.01, 30.0])
def test_e12_closed_form(F_hat, s, k):
    z = np.array([1e-9, 0.1, 0.5, 0.9, 0.95, 0.999999])
    expected = [-k / (s * LEVELS[F_hat] * math.log(zi)) for zi in z]
    got = presliding_velocity(z, k, **P, s=s, F_hat=F_hat)
    np.testing.assert_allclose(got, expected, rtol=1e-14)
    assert presliding_velocity(0.0, k, **P, s=s, F_hat=F_hat) == 0.0


def test_e12_broadcasts_z_against_k():
    z = np.linspace(0, 0.9, 7)
    k = np.array([0.5, 1.0, 3.0])
    v = presliding_velocity(z[None, :], k[:, None], **P, F_hat="self")
    assert v.shape == (3, 7)
    for i, ki in enumerate(k):
        np.testing.assert_array_equal(v[i], presliding_velocity(z, ki, **P, F_hat="self"))


@pytest.mark.parametrize("F_hat", F_HAT_CHOICES)
def test_phase_curves_start_at_rest_and_grow_without_bound(F_hat):
    z, v = phase_family(**P, F_hat=F_hat, n=200)
    assert z.shape == (200,) and v.shape == (15, 200)
    assert z[0] == 0.0 and z[-1] == pytest.approx(0.99, rel=1e-15)
    np.testing.assert_array_equal(v[:, 0], 0.0)
    assert np.all(np.diff(v, axis=1) > 0)  # rising in z for every k
    assert np.all(np.diff(v[:, 1:], axis=0) > 0)  # and in k at every z > 0
    # towards z = 1: ẋ ≈ k/(s·F̂·(1 − z)), i.e. unbounded
    eps = np.array([1e-3, 1e-6, 1e-9])
    for k in (0.01, 28.01):
        v_end = presliding_velocity(1 - eps, k, **P, F_hat=F_hat)
        assert np.all(np.diff(v_end) > 0)
        assert v_end[-1] > 1e7 * k
        if F_hat != "self":
            np.testing.assert_allclose(v_end * eps * LEVELS[F_hat] / k, 1.0, rtol=1e-3)


def test_phase_family_default_rates_are_fig3():
    z, v = phase_family(**P)
    z1, v1 = phase_family(**P, k=FIG3_RATES)
    np.testing.assert_array_equal(v, v1)
    z2, v2 = phase_family(**P, k=[5.0], n=11, z_max=0.5)
    np.testing.assert_allclose(z2, np.linspace(0, 0.5, 11))
    np.testing.assert_allclose(v2[0], presliding_velocity(z2, 5.0, **P), rtol=1e-15)


# ---------------------------------------------------------------------------------
# the self-consistent level
# ---------------------------------------------------------------------------------


def _c(k, z, s=1.0):
    return -k / (s * math.log(z))


@pytest.mark.parametrize("sigma", [0.0, 0.3])
@pytest.mark.parametrize("k", [0.01, 1.0, 10.0, 28.01])
def test_self_root_solves_the_self_consistent_equation(k, sigma):
    z = np.array([0.05, 0.5, 0.95])
    v = presliding_velocity(z, k, **P, sigma=sigma, F_hat="self")
    c = np.array([_c(k, zi) for zi in z])
    np.testing.assert_allclose(v * steady_state_force(v, **P, sigma=sigma), c, rtol=1e-10)
    # for σ = 0 the root lies between the Fs and Fc solutions of E12
    if sigma == 0:
        assert np.all(v >= c / 1.5 * (1 - 1e-12)) and np.all(v <= c / 1.0 * (1 + 1e-12))


@pytest.mark.parametrize("delta, sigma", [(10.0, 0.0), (10.0, 0.3), (20.0, 0.0)])
def test_self_root_is_the_smallest_positive_root_on_a_non_monotone_curve(delta, sigma):
    """A sharp Stribeck dip (large δ, V = 1) makes ẋ·Fss(ẋ) non-monotone: up to three
    roots. The smallest one is the contract (MODEL.md §4); a dense scan finds it."""
    Fc, Fs, V = 1.0, 1.5, 1.0
    vv = np.linspace(0.0, 4.0, 400_001)
    h = vv * steady_state_force(vv, Fc, Fs, V, delta, sigma)
    assert np.any(np.diff(h) < 0)  # really non-monotone
    z_ba = 0.95
    for c in np.linspace(0.05, 3.0, 60):
        k = c * -math.log(z_ba)
        v = float(presliding_velocity(z_ba, k, Fc, Fs, V, delta, sigma=sigma, F_hat="self"))
        assert v * float(steady_state_force(v, Fc, Fs, V, delta, sigma)) == pytest.approx(c,
                                                                                     rel=1e-10)
        first = vv[np.argmax(h >= c)]  # brute force: first grid point at or above c
        assert v == pytest.approx(first, abs=2e-5)


def test_self_root_picks_the_smallest_of_three():
    Fc, Fs, V, delta = 1.0, 1.5, 1.0, 10.0
    c = 1.2
    vv = np.linspace(1e-6, 2.0, 200_001)
    h = vv * steady_state_force(vv, Fc, Fs, V, delta) - c
    roots = vv[np.flatnonzero(np.sign(h[1:]) != np.sign(h[:-1]))]
    assert roots.size == 3
    v = presliding_velocity(0.5, c * math.log(2), Fc, Fs, V, delta, F_hat="self")
    assert v == pytest.approx(roots[0], abs=2e-5)
    assert v == pytest.approx(0.85160, abs=1e-4)  # g(0.8516) ≈ 1.409: still above the dip


# ---------------------------------------------------------------------------------
# E13
# ---------------------------------------------------------------------------------


@pytest.mark.parametrize("F_hat", F_HAT_CHOICES)
def test_e13_is_fss_at_the_e12_velocity(F_hat):
    k = np.array(FIG3_RATES)
    v = breakaway_velocity(k, **P, F_hat=F_hat)
    np.testing.assert_array_equal(v, presliding_velocity(0.95, k, **P, F_hat=F_hat))
    np.testing.assert_array_equal(breakaway_force(k, **P, F_hat=F_hat),
                                  steady_state_force(v, **P))


def test_e13_default_preset_values():
    """Anchors for the README table: F_ba at k = 0.01, 2.01, 28.01 (hand-checked with
    ẋ* = k/(F̂·0.0512933), F_ba = 1 + 0.5·exp(−ẋ*/100))."""
    k = [0.01, 2.01, 28.01]
    for F_hat, lvl in LEVELS.items():
        expected = [1 + 0.5 * math.exp(-ki / (lvl * -math.log(0.95)) / 100) for ki in k]
        np.testing.assert_allclose(breakaway_force(k, **P, F_hat=F_hat), expected, rtol=1e-14)
    np.testing.assert_allclose(breakaway_force(k, **P, F_hat="avg"), [1.49922, 1.36545, 1.00633],
                               atol=1e-5)


@pytest.mark.parametrize("F_hat", F_HAT_CHOICES)
@pytest.mark.parametrize("lam", [1e-3, 0.5, 7.0, 2500.0])
def test_e13_depends_on_s_and_V_only_through_their_product(F_hat, lam):
    k = np.array(FIG3_RATES)
    ref = breakaway_force(k, 1.0, 1.5, 100.0, 1.0, s=1.0, F_hat=F_hat)
    got = breakaway_force(k, 1.0, 1.5, 100.0 / lam, 1.0, s=lam, F_hat=F_hat)
    np.testing.assert_allclose(got, ref, rtol=1e-9)
    # with viscous friction σ·ẋ ∝ σ/s: the invariant pair is (s·V, σ/s)
    ref = breakaway_force(k, 1.0, 1.5, 100.0, 1.0, s=1.0, sigma=0.002, F_hat=F_hat)
    got = breakaway_force(k, 1.0, 1.5, 100.0 / lam, 1.0, s=lam, sigma=0.002 * lam, F_hat=F_hat)
    np.testing.assert_allclose(got, ref, rtol=1e-9)
    changed = breakaway_force(k, 1.0, 1.5, 100.0 / lam, 1.0, s=lam, sigma=0.002, F_hat=F_hat)
    if lam != 1.0:
        assert np.max(np.abs(changed - ref)) > 1e-3


@pytest.mark.parametrize("F_hat", F_HAT_CHOICES)
@pytest.mark.parametrize("delta", [0.5, 1.0, 2.0])
def test_break_away_falls_from_Fs_towards_Fc(F_hat, delta):
    k = np.geomspace(1e-12, 1e8, 400)
    F = breakaway_force(k, **{**P, "delta": delta}, F_hat=F_hat)
    assert np.all(np.diff(F) <= 0) and np.any(np.diff(F) < 0)
    assert F[0] == pytest.approx(1.5, abs=1e-4)
    assert F[-1] == pytest.approx(1.0, abs=1e-9)
    assert np.all((F >= 1.0) & (F <= 1.5))


@pytest.mark.parametrize("F_hat", F_HAT_CHOICES)
def test_velocity_strengthening_break_away_rises_from_Fc_to_Fs(F_hat):
    k = np.geomspace(1e-12, 1e8, 400)
    F = breakaway_force(k, **{**P, "delta": -1.0}, F_hat=F_hat)
    assert np.all(np.diff(F) >= 0) and np.any(np.diff(F) > 0)
    assert F[0] == pytest.approx(1.0, abs=1e-4)
    assert F[-1] == pytest.approx(1.5, abs=1e-6)


def test_viscous_friction_makes_break_away_rise_again():
    # δ = 1: dFss/dẋ = σ − (Fs − Fc)/V·exp(−ẋ/V) changes sign at ẋ = V·ln((Fs − Fc)/(σ·V))
    k = np.geomspace(0.01, 1e3, 400)
    F = breakaway_force(k, **P, sigma=0.001)
    i = int(np.argmin(F))
    v_min = 100.0 * math.log(0.5 / (0.001 * 100.0))
    assert k[i] == pytest.approx(v_min * 1.25 * -math.log(0.95), rel=0.03)
    assert F[i] == pytest.approx(1 + 0.5 * math.exp(-v_min / 100) + 0.001 * v_min, rel=1e-4)
    assert F[-1] > 1.5  # σ·ẋ* dominates at high rates


def test_strong_viscous_friction_leaves_no_dip():
    # σ >= (Fs − Fc)/V: Fss rises everywhere, so does F_ba (the 'viscous' preset, σ = 0.01)
    F = breakaway_force(np.linspace(0.01, 30, 300), **P, sigma=0.01)
    assert np.all(np.diff(F) > 0)
    assert F[0] == pytest.approx(1.5008, abs=1e-4)


def test_fig5_curves_coincide_at_the_ends_and_part_in_between():
    """The note's Fig. 5: the Fc, Fs and avg curves nearly coincide at low and high k
    and differ most in the steep part; larger F̂ means slower presliding, higher F_ba."""
    k = np.array([0.01, 4.01, 28.01])
    F = {name: breakaway_force(k, **P, F_hat=name) for name in ("Fc", "avg", "Fs")}
    spread = F["Fs"] - F["Fc"]
    assert spread[0] < 1e-3 and spread[2] < 0.015 and spread[1] > 0.06
    assert np.all(F["Fs"] >= F["avg"]) and np.all(F["avg"] >= F["Fc"])


# ---------------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------------

FUNCS = {
    "presliding_velocity": lambda **kw: presliding_velocity(0.5, 1.0, **kw),
    "phase_family": lambda **kw: phase_family(**kw),
    "breakaway_force": lambda **kw: breakaway_force(1.0, **kw),
    "breakaway_velocity": lambda **kw: breakaway_velocity(1.0, **kw),
}


@pytest.mark.parametrize("func", sorted(FUNCS))
@pytest.mark.parametrize(
    "bad, name",
    [(dict(Fs=0.5), "Fs"), (dict(V=0.0), "V"), (dict(V=-1.0), "V"), (dict(delta=0.0), "delta"),
     (dict(Fc=NAN), "Fc"), (dict(V=NAN), "V"), (dict(delta=NAN), "delta"), (dict(s=0.0), "s"),
     (dict(s=NAN), "s"), (dict(sigma=-0.1), "sigma"), (dict(F_hat="mean"), "F_hat")],
)
def test_bad_parameters_raise_naming_them(func, bad, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        FUNCS[func](**{**P, **bad})


@pytest.mark.parametrize("k", [0.0, -1.0, NAN, [1.0, NAN]])
def test_bad_rates(k):
    with pytest.raises(ValueError, match=r"^k must"):
        presliding_velocity(0.5, k, **P)
    with pytest.raises(ValueError, match=r"^k must"):
        breakaway_force(k, **P)


@pytest.mark.parametrize("z", [-0.1, 1.0, 1.5, NAN])
def test_bad_presliding_fraction(z):
    with pytest.raises(ValueError, match=r"^z must"):
        presliding_velocity(z, 1.0, **P)


@pytest.mark.parametrize("z_ba", [0.0, 1.0, NAN])
def test_bad_break_away_fraction(z_ba):
    with pytest.raises(ValueError, match=r"^z_ba must"):
        breakaway_force(1.0, **P, z_ba=z_ba)
    with pytest.raises(ValueError, match=r"^z_max must"):
        phase_family(**P, z_max=z_ba)


def test_defaults_match_the_preset():
    # the function defaults are the preset's s, σ, z* and F̂
    assert (DEFAULTS["s"], DEFAULTS["sigma"], DEFAULTS["z_ba"], DEFAULTS["F_hat"]) == (
        1.0, 0.0, 0.95, "avg")
    np.testing.assert_array_equal(
        breakaway_force(FIG3_RATES, **P),
        breakaway_force(FIG3_RATES, **P, s=1.0, sigma=0.0, F_hat="avg", z_ba=0.95))


@pytest.mark.parametrize("params", [
    (1.0, 1.5, 100.0, 1.0, 0.0),  # increasing ẋ·Fss: the Newton path
    (1.0, 1.5, 20.0, -1.0, 0.0),  # velocity strengthening: increasing too
    (0.1, 1.5, 5.0, 8.0, 0.0),  # turns back; roots at the top of the bracket
    (1.0, 3.0, 5.0, 4.0, 0.0),  # turns back; three roots for some c
])
def test_self_root_is_exact_on_both_solver_paths(params):
    # regression: a converged Newton step on the bracket's edge was thrown away, and the
    # grid missed roots where round-off put the bracket's top a hair below the target
    Fc, Fs, V, delta, sigma = params
    k = np.linspace(0.01, 30.0, 200)
    c = k / -np.log(0.95)
    v = presliding_velocity(0.95, k, Fc, Fs, V, delta, 1.0, sigma, "self")
    residual = v * steady_state_force(v, Fc, Fs, V, delta, sigma) - c
    np.testing.assert_allclose(residual / c, 0.0, atol=1e-12)


@pytest.mark.parametrize("delta", [1000.0, -1000.0])
@pytest.mark.parametrize("F_hat", F_HAT_CHOICES)
def test_a_very_sharp_stribeck_curve_is_computed_without_overflow(delta, F_hat):
    # δ = ±1000 makes the Stribeck curve a step at V: y = (v/V)^δ overflows a float where
    # e^(−y) is long 0; it used to warn (overflow, 0·inf) and give a NaN Newton slope
    k = np.array([0.05, 1.0, 4.0, 10.0, 30.0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        F = breakaway_force(k, 1.0, 1.5, 2.0, delta, F_hat=F_hat)
        v = presliding_velocity(0.95, k, 1.0, 1.5, 2.0, delta, F_hat=F_hat)
    c = k / -np.log(0.95)
    # the step: Fs below V and Fc above it (δ > 0), the other way round for δ < 0
    below, above = (1.5, 1.0) if delta > 0 else (1.0, 1.5)
    if F_hat == "self":
        # the smallest root of v·g(v) = c: c/below while it stays below V, else c/above
        expected = np.where(c / below < 2.0, c / below, c / above)
    else:
        expected = c / LEVELS[F_hat]
    np.testing.assert_allclose(v, expected, rtol=1e-12)
    np.testing.assert_allclose(F, np.where(expected < 2.0, below, above), rtol=1e-12)
