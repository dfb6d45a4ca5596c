"""One explorer redraw (explore_frame): sizes, contents and bad parameters."""

import numpy as np
import pytest

from breakaway.frame import FRAME_GRID, breakaway_curves, explore_frame, stribeck_curve
from breakaway.params import DEFAULTS, FIG3_RATES
from breakaway.quasistatic import breakaway_force, presliding_velocity
from breakaway.steady import steady_state_force

NAN = float("nan")


def test_frame_sizes_are_the_benchmarked_grid():
    assert FRAME_GRID == {"stribeck": 400, "loop": 2000, "phase": 200, "breakaway": 200}
    f = explore_frame()
    assert f["stribeck"]["v"].shape == f["stribeck"]["F"].shape == (400,)
    assert f["hysteresis"]["x"].shape == f["hysteresis"]["F"].shape == (2000,)
    assert f["phase"]["z"].shape == (200,)
    assert len(f["phase"]["curves"]) == 16  # the Fig. 3 family plus the current k
    assert all(c["v"].shape == (200,) for c in f["phase"]["curves"])
    assert f["breakaway"]["k"].shape == (200,)
    for name in ("Fc", "Fs", "avg", "self"):
        assert f["breakaway"][name].shape == (200,)


def test_frame_contents_are_the_model_functions():
    params = {"Fs": 2.0, "V": 3.0, "delta": 2.0, "sigma": 0.05, "s": 10.0, "k": 7.0,
              "F_hat": "self"}
    f = explore_frame(params)
    p = {**DEFAULTS, **params}
    curve = (p["Fc"], p["Fs"], p["V"], p["delta"])
    v = f["stribeck"]["v"]
    assert v[-1] == pytest.approx(5 * 3.0, rel=1e-15) and v[0] == -v[-1]
    np.testing.assert_allclose(f["stribeck"]["F"], steady_state_force(v, *curve, 0.05),
                               rtol=1e-15)
    rates = [c["k"] for c in f["phase"]["curves"]]
    np.testing.assert_allclose(rates, list(FIG3_RATES) + [7.0], rtol=1e-15)
    z = f["phase"]["z"]
    np.testing.assert_allclose(f["phase"]["curves"][-1]["v"],
                               presliding_velocity(z, 7.0, *curve, 10.0, 0.05, "self"),
                               rtol=1e-12)
    k = f["breakaway"]["k"]
    assert (k[0], k[-1]) == pytest.approx((0.01, 30.0), rel=1e-15)
    for name in ("Fc", "Fs", "avg", "self"):
        np.testing.assert_allclose(f["breakaway"][name],
                                   breakaway_force(k, *curve, 10.0, 0.05, name, 0.95),
                                   rtol=1e-15)
    # the loop reaches gross sliding (amplitude 1.5/s) and respects the steady bound
    assert np.max(np.abs(f["hysteresis"]["x"])) == pytest.approx(0.15, rel=1e-5)
    assert np.max(np.abs(f["hysteresis"]["F"])) <= 2.0 + 0.05 * 3.0 * 0.1 + 1e-12


@pytest.mark.parametrize(
    "bad, name",
    [({"Fs": 0.5}, "Fs"), ({"V": 0.0}, "V"), ({"V": -1.0}, "V"), ({"V": NAN}, "V"),
     ({"delta": 0.0}, "delta"), ({"Fc": NAN}, "Fc"), ({"s": 0.0}, "s"), ({"k": 0.0}, "k"),
     ({"z_ba": 1.0}, "z_ba"), ({"sigma": -1.0}, "sigma"), ({"F_hat": "max"}, "F_hat")],
)
def test_frame_bad_parameters_are_named(bad, name):
    with pytest.raises(ValueError, match=rf"^{name} must"):
        explore_frame(bad)


def test_frame_rejects_unknown_keys():
    with pytest.raises(ValueError, match="'vs'"):
        explore_frame({"vs": 1.0})


def test_curve_helpers_validate():
    with pytest.raises(ValueError, match=r"^V must"):
        stribeck_curve(1.0, 1.5, 0.0, 1.0, 0.0)
    with pytest.raises(ValueError, match=r"^k_max must"):
        breakaway_curves(1.0, 1.5, 1.0, 1.0, 1.0, 0.0, 0.95, k_min=2.0, k_max=1.0)
