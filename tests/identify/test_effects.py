"""The effect library: one object per effect, and which effects the data can show."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify.csvdata import Dataset
from breakaway.identify.effects import EFFECTS, availability, param_spec
from breakaway.identify.models import problem_for
from breakaway.identify.synthetic import make_dataset


def _dataset(kind, meta=None, **columns):
    n = len(next(iter(columns.values())))
    return Dataset(kind=kind, columns={k: np.asarray(v, float) for k, v in columns.items()},
                   meta=dict(meta or {}), n=n, ignored_columns=(), lines=np.arange(n) + 2)


def _available(data):
    return [name for name, why in availability(problem_for(data)).items() if why is None]


def test_library_names_and_keys_follow_the_contract():
    assert {name: e.keys for name, e in EFFECTS.items()} == {
        "viscous": ("sigma",), "viscous-power": ("sigma", "n"), "asymmetry": ("Fc_neg", "Fs_neg"), "offset": ("F_offset",),
        "drift": ("alpha",), "inertia": ("m_e",), "ripple": ("A", "wavelength", "phase"),
        "lag": ("tau",), "backlash": ("play",), "dwell": ("zeta", "tau_d"),
        "detection": ("tau_det",)}


def test_every_parameter_has_a_unit_and_bounds_and_every_effect_a_regressor():
    for effect in EFFECTS.values():
        assert set(effect.regressor) == set(effect.kinds)
        for p in effect.params:
            assert param_spec(p.name, (effect.name,)) is p


@pytest.mark.parametrize("kind,expected", [
    ("timeseries", ["viscous", "viscous-power", "asymmetry", "offset", "drift", "inertia", "ripple", "lag",
                    "backlash"]),
    ("steady", ["viscous", "viscous-power", "asymmetry", "offset"]),
    ("breakaway", ["viscous", "asymmetry", "inertia", "dwell", "detection"]),
])
def test_available_per_kind(kind, expected):
    data, _ = make_dataset(kind, (), seed=0, n=10_000 if kind == "timeseries" else None)
    assert _available(data) == expected


def test_one_direction_only_has_no_asymmetry_or_offset():
    v = np.geomspace(1e-4, 0.1, 20)
    reasons = availability(problem_for(_dataset("steady", v=v, F=v)))
    assert reasons["asymmetry"].startswith("one-direction")
    assert reasons["offset"].startswith("one-direction")
    x = np.linspace(0, 1, 50)
    assert "asymmetry" not in _available(_dataset("timeseries", t=x, x=x, F=x))


def test_breakaway_needs_the_columns_and_rates_its_effects_read():
    k = np.linspace(0.1, 10, 20)
    assert _available(_dataset("breakaway", k=k, F_ba=k)) == ["viscous", "inertia", "detection"]
    same_dwell = _dataset("breakaway", k=k, F_ba=k, dwell=np.full(20, 5.0))
    assert "dwell" not in _available(same_dwell)
    one_way = _dataset("breakaway", k=k, F_ba=k, direction=np.ones(20))
    assert "asymmetry" not in _available(one_way)
    one_rate = availability(problem_for(_dataset("breakaway", k=np.full(20, 5.0), F_ba=k)))
    for name in ("viscous", "inertia", "detection"):
        assert one_rate[name].startswith("single-rate"), name


def test_a_short_record_that_mostly_moves_one_way_is_one_direction():
    data, _ = make_dataset("timeseries", (), seed=0, n=2000)
    pos, neg, total = problem_for(data).direction_counts()
    assert neg < 0.05 * total
    assert availability(problem_for(data))["asymmetry"].startswith("one-direction")


def test_the_periodogram_is_scipys_lomb_scargle_and_finds_the_ripple():
    from scipy.signal import lombscargle

    from breakaway.identify.effects import periodogram

    # a residual periodic in x with a wavelength of 3 mm, at irregular places over 30 mm
    rng = np.random.default_rng(5)
    x = rng.uniform(0.0, 0.03, 3000)
    r = 0.5 * np.sin(2 * np.pi * x / 3e-3 + 0.4) + rng.standard_normal(x.size)
    wavelengths = np.geomspace(2e-4, 1e-2, 400)
    power = periodogram(x, r, wavelengths)
    expected = lombscargle(x, r - r.mean(), 2 * np.pi / wavelengths)
    np.testing.assert_allclose(power, expected, rtol=1e-9, atol=1e-12 * expected.max())
    assert wavelengths[np.argmax(power)] == pytest.approx(3e-3, rel=0.02)
    # a long record is thinned to about 4,000 rows, as scipy's would be given them
    long_x, long_r = np.repeat(x, 5), np.repeat(r, 5)
    thinned = lombscargle(long_x[::3], long_r[::3] - long_r.mean(), 2 * np.pi / wavelengths)
    np.testing.assert_allclose(periodogram(long_x, long_r, wavelengths), thinned, rtol=1e-9,
                               atol=1e-12 * thinned.max())
