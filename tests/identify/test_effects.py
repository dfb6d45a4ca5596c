"""The effect library and which candidates the data can determine."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify.effects import EFFECTS, candidates
from breakaway.identify.synthetic import make_dataset


def test_library_names_and_keys_follow_the_contract():
    assert {name: e.params for name, e in EFFECTS.items()} == {
        "viscous": ("sigma",), "asymmetry": ("Fc_neg", "Fs_neg"), "offset": ("F_offset",),
        "drift": ("alpha",), "inertia": ("m_e",), "ripple": ("A", "wavelength", "phase"),
        "lag": ("tau",), "backlash": ("play",), "dwell": ("zeta", "tau_d")}


@pytest.mark.parametrize("kind,expected", [
    ("timeseries", ["viscous", "asymmetry", "offset", "drift", "inertia", "ripple", "lag",
                    "backlash"]),
    ("steady", ["viscous", "asymmetry", "offset"]),
    ("breakaway", ["viscous", "asymmetry", "inertia", "dwell"]),
])
def test_candidates_per_kind(kind, expected):
    data, _ = make_dataset(kind, (), seed=0, n=2000 if kind == "timeseries" else None)
    assert candidates(kind, data.columns) == expected


def test_one_direction_only_has_no_asymmetry_candidate():
    v = np.geomspace(1e-4, 0.1, 20)
    assert "asymmetry" not in candidates("steady", {"v": v, "F": v})
    x = np.linspace(0, 1, 50)
    assert "asymmetry" not in candidates("timeseries", {"t": x, "x": x, "F": x})


def test_breakaway_needs_the_columns_its_effects_read():
    k = np.linspace(0.1, 10, 20)
    assert candidates("breakaway", {"k": k, "F_ba": k}) == ["viscous", "inertia"]
    same_dwell = {"k": k, "F_ba": k, "dwell": np.full(20, 5.0)}
    assert "dwell" not in candidates("breakaway", same_dwell)
    one_way = {"k": k, "F_ba": k, "direction": np.ones(20)}
    assert "asymmetry" not in candidates("breakaway", one_way)
