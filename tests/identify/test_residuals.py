"""Noise floor and whiteness of the residual."""

from __future__ import annotations

import math

import numpy as np
import pytest

from breakaway.identify.models import problem_for as Problem
from breakaway.identify.noise import noise_floor
from breakaway.identify.residuals import is_white
from breakaway.identify.synthetic import make_dataset, with_force


@pytest.mark.parametrize("kind", ["timeseries", "steady", "breakaway"])
@pytest.mark.parametrize("sigma_factor", [0.3, 1.0, 4.0])
def test_noise_floor_is_model_free_and_close(kind, sigma_factor):
    from breakaway.identify.synthetic import NOISE

    sigma = NOISE[kind] * sigma_factor
    data, _ = make_dataset(kind, ("viscous",), seed=8, noise=sigma,
                           n=8000 if kind == "timeseries" else None)
    # the estimate never sees a model: an effect in the data does not change it much
    assert noise_floor(Problem(data)) == pytest.approx(sigma, rel=0.2)


def test_quantised_noiseless_force_gives_the_quantisation_noise():
    data, _ = make_dataset("steady", (), seed=0, noise=0.0)
    step = 0.5
    quantised = with_force(data, np.round(data.columns["F"] / step) * step)
    floor = noise_floor(Problem(quantised))
    assert 0 < floor <= step


def test_white_noise_is_white_and_structure_is_not():
    data, _ = make_dataset("timeseries", (), seed=9, n=8000)
    problem = Problem(data)
    rng = np.random.default_rng(0)
    noise = 0.05 * rng.standard_normal(data.n)
    assert is_white(noise, problem, 0.05)
    slow = noise + 0.03 * np.sin(2 * math.pi * data.columns["t"] / 2.0)
    assert not is_white(slow, problem, 0.05)
    # the right shape but far above the floor: not white either
    assert not is_white(3 * noise, problem, 0.05)
