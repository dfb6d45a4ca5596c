"""Set-points: F(v) of (E2) both ways; the speeds a rig can hold."""

import numpy as np

from breakaway.plan.curve import magnitude
from breakaway.plan.setpoints import SetPoints
from breakaway.plan.setting import Limits, Setting

P = {name: np.array([[v]]) for name, v in
     {"Fc": 10.0, "Fs": 15.0, "V": 0.005, "delta": 1.0, "sigma": 100.0, "n": 1.0}.items()}


def _setting(u_max, v_min=1e-4, v_max=0.1):
    return Setting(Limits(u_max, v_max, v_min, None, 60.0, 1e3), noise=0.05,
                   units={"F": "N", "v": "m/s"}, grid=50)


def test_a_run_is_two_measurements_of_the_curve():
    family = SetPoints()
    cands = family.candidates(P, _setting(30.0))
    info = family.information(cands, P, _setting(30.0), ["Fc", "Fs", "V", "delta", "sigma"])
    _, _, partial = magnitude(cands.points["v"], P)
    j = np.stack([partial[n][0] for n in ("Fc", "Fs", "V", "delta", "sigma")], axis=-1)
    np.testing.assert_allclose(info.matrix[0], 2 * j[:, :, None] * j[:, None, :] / 0.05**2,
                               rtol=1e-12)


def test_a_speed_that_takes_more_than_u_max_at_a_draw_yields_nothing_there():
    draws = {**P, "sigma": np.array([[100.0], [400.0]]), "Fc": np.full((2, 1), 10.0)}
    draws = {name: np.broadcast_to(value, (2, 1)) for name, value in draws.items()}
    family = SetPoints()
    cands = family.candidates(draws, _setting(12.0), middle=0)
    info = family.information(cands, draws, _setting(12.0), ["Fc", "Fs"], middle=0)
    assert info.usable[0].all()
    # σ = 400 N·s/m: above (12 − 10)/400 = 5 mm/s the rig cannot hold the speed
    np.testing.assert_array_equal(info.usable[1], magnitude(cands.points["v"], draws)[0][1] <= 12)
    assert not info.usable[1].all() and np.all(info.matrix[1][~info.usable[1]] == 0)


def test_speeds_stay_between_v_min_and_v_max_and_below_the_force_limit():
    family = SetPoints()
    # σ·v pushes the force over 12 N above (12 − 10)/100 = 0.02 m/s
    cands = family.candidates(P, _setting(12.0))
    v = cands.points["v"]
    assert v.min() >= 1e-4 and v.max() <= 0.1
    assert np.all(magnitude(v, P)[0] <= 12.0)
    assert v.max() < 0.02


def test_no_speed_within_the_force_limit_is_said():
    cands = SetPoints().candidates(P, _setting(5.0))
    assert cands.size == 0 and "exceeds u_max = 5" in cands.why_none
