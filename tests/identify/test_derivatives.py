"""v and a of a position record (MODEL.md §7 ``derivatives``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from breakaway.identify.derivatives import (NOISE_TO_SIGNAL, WINDOWS, acceleration_noise,
                                            choose_window, derivatives, local_fit, smooth_fit)

RATE = 1000.0


def _swing(count, n=6000, amplitude=0.05, frequency=0.8, jitter=0.0, seed=0):
    """A sinusoidal swing [rad] read by an encoder of ``count`` at 1 kHz (optionally
    with uneven sampling), and its true acceleration."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / RATE + jitter / RATE * rng.uniform(-0.5, 0.5, n)
    w = 2 * np.pi * frequency
    x = amplitude * np.sin(w * t)
    a = -amplitude * w**2 * np.sin(w * t)
    return t, np.round(x / count) * count, a


def _rms(values):
    return math.sqrt(float(np.mean(values**2)))


def test_exact_x_keeps_numpy_gradient():
    t = np.arange(200) / RATE
    x = np.sin(3 * t) ** 2
    d = derivatives(t, x)
    np.testing.assert_array_equal(d.v, np.gradient(x, t))
    np.testing.assert_array_equal(d.a, np.gradient(np.gradient(x, t), t))
    assert d.entry()["method"] == "gradient"


@pytest.mark.parametrize("counts_per_rev", [10_000, 4096])
def test_encoder_acceleration_is_the_signal_not_the_counts(counts_per_rev):
    count = 2 * np.pi / counts_per_rev
    t, x, a_true = _swing(count)
    d = derivatives(t, x, quantum=count)
    inner = slice(600, -600)  # away from the ends, where any local fit extrapolates
    error = _rms(d.a[inner] - a_true[inner])
    twice_differenced = np.gradient(np.gradient(x, t), t)
    assert d.method == "savgol" and d.window in WINDOWS and d.window > 5
    # measured: 6 and 9 % of the signal's RMS; twice differenced, 100 times the signal
    assert error < 0.1 * _rms(a_true)
    assert _rms(twice_differenced[inner] - a_true[inner]) > 10 * _rms(a_true)


def test_the_window_is_the_narrowest_that_holds_the_noise_below_its_share():
    count = 2 * np.pi / 10_000
    t, x, a_true = _swing(count)
    window = choose_window(t, x, count / math.sqrt(12))
    noise = acceleration_noise(window, count / math.sqrt(12), 1 / RATE)
    assert noise <= NOISE_TO_SIGNAL * _rms(a_true)
    narrower = WINDOWS[WINDOWS.index(window) - 1]
    assert acceleration_noise(narrower, count / math.sqrt(12), 1 / RATE) \
        > NOISE_TO_SIGNAL * 0.9 * _rms(a_true)
    # a coarser encoder needs a wider window
    coarse = 2 * np.pi / 1000
    _, x_coarse, _ = _swing(coarse)
    assert choose_window(t, x_coarse, coarse / math.sqrt(12)) > window


def test_uneven_sampling_is_fitted_in_t():
    count = 2 * np.pi / 10_000
    t, x, a_true = _swing(count, jitter=0.3)
    d = derivatives(t, x, quantum=count)
    inner = slice(600, -600)
    assert _rms(d.a[inner] - a_true[inner]) < 0.1 * _rms(a_true)
    even_t, even_x, _ = _swing(count)
    v_even, a_even = local_fit(even_t, even_x, 47)
    # the same fit as Savitzky–Golay where the sampling is even
    from breakaway.identify.derivatives import _local_quadratic
    p_loop, v_loop, a_loop = _local_quadratic(even_t, even_x, 23)
    p_even = smooth_fit(even_t, even_x, 47)[0]
    np.testing.assert_allclose(p_loop[30:-30], p_even[30:-30], rtol=0, atol=1e-12)
    np.testing.assert_allclose(a_loop[30:-30], a_even[30:-30], rtol=1e-6, atol=1e-6)
    np.testing.assert_allclose(v_loop[30:-30], v_even[30:-30], rtol=1e-6, atol=1e-9)


def test_blocks_are_differentiated_apart():
    count = 2 * np.pi / 10_000
    t, x, _ = _swing(count, n=4000)
    joined = derivatives(t, x, quantum=count, blocks=[(0, 2000), (2000, 4000)])
    first = derivatives(t[:2000], x[:2000], quantum=count, window=joined.window)
    np.testing.assert_array_equal(joined.a[:2000], first.a)
    np.testing.assert_array_equal(joined.v[:2000], first.v)
