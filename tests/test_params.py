"""Defaults, presets and parameter validation (MODEL.md §1)."""

import math

import pytest

from breakaway import params
from breakaway.params import (
    DEFAULTS,
    F_HAT_CHOICES,
    FIG3_RATES,
    LUGRE_1995,
    PRESETS,
    check_f_hat,
    check_fraction,
    check_positive,
    check_stribeck,
    with_defaults,
)

NAN = float("nan")
INF = float("inf")


def test_defaults_are_the_documented_preset():
    expected = {"Fc": 1.0, "Fs": 1.5, "V": 100.0, "delta": 1.0, "sigma": 0.0, "s": 1.0,
                "z_ba": 0.95, "m": 1e-4, "k": 1.0, "F_hat": "avg"}
    assert DEFAULTS == expected


def test_defaults_satisfy_the_constraints_of_section_1():
    check_stribeck(DEFAULTS["Fc"], DEFAULTS["Fs"], DEFAULTS["V"], DEFAULTS["delta"],
                   DEFAULTS["sigma"])
    check_positive(s=DEFAULTS["s"], m=DEFAULTS["m"], k=DEFAULTS["k"])
    check_fraction("z_ba", DEFAULTS["z_ba"])
    check_f_hat(DEFAULTS["F_hat"])


def test_fig3_rates_are_the_notes_grid():
    assert len(FIG3_RATES) == 15
    assert FIG3_RATES[0] == pytest.approx(0.01, abs=1e-15)
    assert FIG3_RATES[-1] == pytest.approx(28.01, abs=1e-12)
    steps = [b - a for a, b in zip(FIG3_RATES, FIG3_RATES[1:])]
    assert steps == pytest.approx([2.0] * 14, abs=1e-12)


def test_lugre_1995_parameters():
    assert LUGRE_1995["sigma0"] == 1e5
    assert LUGRE_1995["sigma1"] == pytest.approx(316.22776601683796, rel=1e-15)
    assert (LUGRE_1995["sigma2"], LUGRE_1995["Fc"], LUGRE_1995["Fs"]) == (0.4, 1.0, 1.5)
    assert (LUGRE_1995["vs"], LUGRE_1995["delta"], LUGRE_1995["m"]) == (1e-3, 2.0, 1.0)


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_every_preset_is_complete_and_valid(name):
    preset = PRESETS[name]
    assert set(preset) == set(DEFAULTS)
    check_stribeck(preset["Fc"], preset["Fs"], preset["V"], preset["delta"], preset["sigma"])
    check_positive(s=preset["s"], m=preset["m"], k=preset["k"])
    check_fraction("z_ba", preset["z_ba"])
    check_f_hat(preset["F_hat"])
    assert name in params.PRESET_DESCRIPTIONS


def test_preset_values():
    assert PRESETS["fig5"] == DEFAULTS
    assert PRESETS["no-stribeck"]["Fs"] == PRESETS["no-stribeck"]["Fc"] == 1.0
    assert PRESETS["strengthening"]["delta"] == -1.0
    # the LuGre bristles reach Fs at a deflection Fs/sigma0 = 15 µm
    assert 1.0 / PRESETS["lugre-1995"]["s"] == pytest.approx(1.5e-5, rel=1e-12)


def test_equal_levels_are_allowed():
    check_stribeck(1.0, 1.0, 1.0, 1.0)  # Fs = Fc: no Stribeck dip, still valid
    check_stribeck(1.0, 2.0, 1.0, -0.05)  # velocity strengthening


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(Fc=1.0, Fs=0.9, V=1.0, delta=1.0), "Fs"),
        (dict(Fc=0.0, Fs=1.5, V=1.0, delta=1.0), "Fc"),
        (dict(Fc=-1.0, Fs=1.5, V=1.0, delta=1.0), "Fc"),
        (dict(Fc=1.0, Fs=1.5, V=0.0, delta=1.0), "V"),
        (dict(Fc=1.0, Fs=1.5, V=-2.0, delta=1.0), "V"),
        (dict(Fc=1.0, Fs=1.5, V=1.0, delta=0.0), "delta"),
        (dict(Fc=1.0, Fs=1.5, V=1.0, delta=1.0, sigma=-0.1), "sigma"),
        (dict(Fc=NAN, Fs=1.5, V=1.0, delta=1.0), "Fc"),
        (dict(Fc=1.0, Fs=NAN, V=1.0, delta=1.0), "Fs"),
        (dict(Fc=1.0, Fs=1.5, V=NAN, delta=1.0), "V"),
        (dict(Fc=1.0, Fs=1.5, V=1.0, delta=NAN), "delta"),
        (dict(Fc=1.0, Fs=1.5, V=1.0, delta=1.0, sigma=NAN), "sigma"),
        (dict(Fc=1.0, Fs=INF, V=1.0, delta=1.0), "Fs"),
        (dict(Fc=1.0, Fs=1.5, V=INF, delta=1.0), "V"),
        (dict(Fc="one", Fs=1.5, V=1.0, delta=1.0), "Fc"),
        (dict(Fc=1.0, Fs=None, V=1.0, delta=1.0), "Fs"),
    ],
)
def test_check_stribeck_names_the_bad_parameter(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        check_stribeck(**kwargs)


@pytest.mark.parametrize("value", [0.0, -1e-9, NAN, INF, "x"])
def test_check_positive_names_the_parameter(value):
    with pytest.raises(ValueError, match=r"^m must"):
        check_positive(s=1.0, m=value)


@pytest.mark.parametrize("value", [0.0, 1.0, -0.5, 1.5, NAN])
def test_check_fraction_is_open_interval(value):
    with pytest.raises(ValueError, match=r"^z_ba must"):
        check_fraction("z_ba", value)


def test_check_fraction_accepts_inside():
    for value in (1e-9, 0.5, 0.95, 1 - 1e-12):
        check_fraction("z_ba", value)


@pytest.mark.parametrize("choice", F_HAT_CHOICES)
def test_check_f_hat_accepts_the_four_choices(choice):
    check_f_hat(choice)


@pytest.mark.parametrize("choice", ["fc", "mean", "", None])
def test_check_f_hat_rejects_others(choice):
    with pytest.raises(ValueError, match="F_hat"):
        check_f_hat(choice)


def test_with_defaults_merges_and_rejects_unknown_keys():
    merged = with_defaults({"Fs": 2.0}, V=3.0)
    assert merged["Fs"] == 2.0 and merged["V"] == 3.0 and merged["Fc"] == 1.0
    assert DEFAULTS["Fs"] == 1.5  # the defaults themselves are untouched
    with pytest.raises(ValueError, match="'Vs'"):
        with_defaults({"Vs": 1.0})


def test_default_quasistatic_velocity_spans_the_stribeck_velocity():
    """Why V = 100 m/s: E12's break-away velocity ẋ* = k/(s·F̂·|ln z*|) with F̂ = avg
    is ≈ 0.16 m/s (far below V, F_ba ≈ Fs) at k = 0.01 and ≈ 440 m/s (4.4 V, F_ba
    within 1 % of Fc) at k = 28.01, so the Fig. 3 rates sweep the whole Fig. 5 curve."""
    f_hat = DEFAULTS["Fc"] + (DEFAULTS["Fs"] - DEFAULTS["Fc"]) / 2
    v_star = [k / (DEFAULTS["s"] * f_hat * -math.log(DEFAULTS["z_ba"])) for k in
              (FIG3_RATES[0], FIG3_RATES[-1])]
    assert v_star[0] == pytest.approx(0.155966, rel=1e-5)
    assert v_star[1] == pytest.approx(436.86, rel=1e-4)
    assert v_star[0] / DEFAULTS["V"] < 2e-3 and v_star[1] / DEFAULTS["V"] > 4
