"""Isolated spikes of the measured force: found where they are, nowhere else, set aside,
and said (issue: a report must not call a few glitches "structure")."""

from __future__ import annotations

import numpy as np
import pytest

from breakaway.identify import diagnose, report
from breakaway.identify.outliers import (MAX_SHARE, SPIKE_SIGMAS, despiked_force, find_spikes,
                                         running_median)
from breakaway.identify.synthetic import NOISE, make_dataset, with_force

N_TIMESERIES = 10_000


def spaced_rows(rng, n: int, count: int, gap: int = 8) -> np.ndarray:
    """``count`` distinct rows of ``n``, at least ``gap`` apart (isolated by design)."""
    slots = rng.choice(n // gap, count, replace=False)
    return np.sort(slots * gap + gap // 2)


def with_spikes(values, rows, size, rng):
    out = np.array(values, dtype=float)
    out[rows] += size * rng.choice([-1.0, 1.0], rows.size)
    return out


def test_running_median_of_the_neighbours_leaves_the_row_out():
    values = np.array([1.0, 2.0, 100.0, 3.0, 4.0])
    assert running_median(values, 1).tolist() == [1.5, 2.0, 3.0, 4.0, 3.5]
    assert running_median(values, 1, neighbours_only=True).tolist() == [2.0, 50.5, 2.5, 52.0, 3.0]


def test_running_median_skips_set_aside_rows_as_nanmedian_does():
    # the fast path takes numpy's plain median wherever a window holds no NaN
    rng = np.random.default_rng(4)
    values = rng.standard_normal(2000)
    values[rng.choice(values.size, 150, replace=False)] = np.nan
    values[500:508] = np.nan  # a window of nothing but set-aside rows
    padded = np.pad(values, 3, constant_values=np.nan)
    windows = np.delete(np.lib.stride_tricks.sliding_window_view(padded, 7), 3, axis=1)
    with np.errstate(invalid="ignore"), pytest.warns(RuntimeWarning, match="All-NaN"):
        expected = np.nanmedian(windows, axis=1)
    with pytest.warns(RuntimeWarning, match="All-NaN"):
        got = running_median(values, 3, neighbours_only=True)
    assert np.isnan(got[503])
    np.testing.assert_array_equal(got, expected)


def test_white_noise_has_no_spikes():
    rng = np.random.default_rng(0)
    residual = rng.standard_normal(200_000)
    spikes, scale = find_spikes(residual, [np.arange(residual.size)])
    assert not spikes.any()
    # the scale is the spread of a row about its neighbours' median (≈ 1.1 σ)
    assert np.median(scale) == pytest.approx(1.10, rel=0.03)


def test_isolated_spikes_are_found_on_structure_steps_and_corners():
    rng = np.random.default_rng(1)
    n = 20_000
    t = np.linspace(0.0, 1.0, n)
    # large smooth structure, a step and a corner (a ramp that stops, as a residual at a
    # reversal does), which the one-sided medians follow
    smooth = 40.0 * np.sin(2 * np.pi * 3 * t) + 25.0 * (t > 0.5) \
        + 0.4 * np.clip(np.arange(n) - 15_000, 0, 200)
    rows = spaced_rows(rng, n, 150)
    residual = with_spikes(smooth + rng.standard_normal(n), rows, 12.0, rng)
    spikes, _ = find_spikes(residual, [np.arange(n)])
    found = np.flatnonzero(spikes)
    assert set(found) <= set(rows)
    # a spike is missed only when a neighbour is itself beyond 3 σ by chance
    assert found.size >= 0.97 * rows.size
    clean, _ = find_spikes(smooth + rng.standard_normal(n), [np.arange(n)])
    assert not clean.any()


def test_noise_that_grows_tenfold_is_not_taken_for_spikes():
    rng = np.random.default_rng(2)
    n = 50_000
    spread = 0.1 + 0.9 * (np.sin(np.linspace(0, 6 * np.pi, n)) ** 2)
    spikes, _ = find_spikes(spread * rng.standard_normal(n), [np.arange(n)])
    assert not spikes.any()


def test_a_peak_a_few_rows_wide_is_not_a_spike():
    # a fast feature of the friction (a break-away at motion onset) spans several rows
    rng = np.random.default_rng(3)
    residual = rng.standard_normal(5_000)
    residual[2000:2005] += np.array([4.0, 9.0, 14.0, 9.0, 4.0])
    spikes, _ = find_spikes(residual, [np.arange(residual.size)])
    assert not spikes[1995:2010].any()


def test_more_than_the_share_of_rows_is_heavy_tailed_noise_not_spikes():
    rng = np.random.default_rng(4)
    n = 10_000
    rows = spaced_rows(rng, n, int(1.5 * MAX_SHARE * n), gap=4)
    residual = with_spikes(rng.standard_normal(n), rows, 20.0, rng)
    spikes, _ = find_spikes(residual, [np.arange(n)])
    assert not spikes.any()


def test_the_noise_floor_bounds_the_scale_of_a_quantised_residual():
    # a residual that is mostly exactly zero (a quantised force) has no spread of its
    # own: nothing is judged without a floor, and its steps are spikes only when they
    # stand more than SPIKE_SIGMAS floors from their neighbours
    residual = np.zeros(2_000)
    residual[::101] = 0.5
    rows = [np.arange(residual.size)]
    assert not find_spikes(residual, rows, floor=0.0)[0].any()
    assert find_spikes(residual, rows, floor=0.01)[0].sum() == 19  # row 0 has one side
    assert not find_spikes(residual, rows, floor=0.5 / SPIKE_SIGMAS)[0].any()


def test_a_ramp_that_ends_the_record_is_not_a_spike_but_one_row_in_is():
    # the last row has neighbours on one side only: a steep ramp and a spike look alike
    rng = np.random.default_rng(7)
    residual = rng.standard_normal(40)
    residual[-6:] += np.array([0.0, 10.0, 20.0, 30.0, 40.0, 50.0])
    assert not find_spikes(residual, [np.arange(40)])[0].any()
    residual[2] += 30.0
    assert np.flatnonzero(find_spikes(residual, [np.arange(40)])[0]).tolist() == [2]


def test_one_spike_in_a_short_record_is_found():
    rng = np.random.default_rng(5)
    residual = rng.standard_normal(20)
    residual[10] += 50.0
    assert np.flatnonzero(find_spikes(residual, [np.arange(20)])[0]).tolist() == [10]


def test_despiked_force_takes_the_median_of_the_neighbours_only_at_spikes():
    force = np.array([1.0, 2.0, 3.0, 50.0, 5.0, 6.0, 7.0])
    spikes = np.zeros(force.size, dtype=bool)
    spikes[3] = True
    out = despiked_force(force, spikes, half_window=2)
    assert out.tolist() == [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]


def _spiky(kind, effects, seed, share=0.01, size=20.0):
    n = N_TIMESERIES if kind == "timeseries" else None
    data, truth = make_dataset(kind, effects, seed=seed, n=n)
    column = "F_ba" if kind == "breakaway" else "F"
    force = data.columns[column]
    rng = np.random.default_rng(seed + 100)
    rows = spaced_rows(rng, force.size, max(1, int(share * force.size)), gap=4)
    spiky = with_spikes(force, rows, size * NOISE[kind], rng)
    if kind == "breakaway":
        spiky = np.abs(spiky)
    return with_force(data, spiky), truth, rows


@pytest.mark.parametrize("kind,effects", [
    ("timeseries", ()), ("steady", ()), ("breakaway", ()),
    ("timeseries", ("asymmetry",)), ("steady", ("offset",)),
    # the base model's misfit hides the spike; the final model's residual shows it
    ("breakaway", ("viscous",)),
])
def test_spikes_are_set_aside_and_said_and_the_effect_still_found(kind, effects):
    data, truth, rows = _spiky(kind, effects, seed=21)
    result = report(diagnose(data))
    assert result["effects"] == list(effects)
    # no structure is claimed where there are only glitches
    assert result["unexplained"] is False
    assert result["residual_white"] is True
    assert result["residual_structure"] == []
    assert result["error_after"] <= 1.3 * NOISE[kind]
    outliers = [w for w in result["warnings"] if w["code"] == "outliers"]
    assert len(outliers) == 1
    assert outliers[0]["parameter"] == ("F_ba" if kind == "breakaway" else "F")
    count = int(outliers[0]["message"].split(" of ")[0])
    assert len(rows) * 0.9 <= count <= len(rows)
    assert f"{count} of {data.n} rows" in outliers[0]["message"]
    # steady and break-away rows are left out, a time series keeps its rows
    assert result["n"] == (data.n if kind == "timeseries" else data.n - count)
    for name in ("Fc", "Fs"):
        assert result["final"]["params"][name] == pytest.approx(truth[name], rel=0.02)


@pytest.mark.parametrize("kind,effects", [
    ("timeseries", ()), ("steady", ()), ("breakaway", ()),
    ("timeseries", ("backlash",)), ("timeseries", ("lag",)), ("breakaway", ("dwell",)),
])
def test_clean_data_have_no_outliers(kind, effects):
    n = N_TIMESERIES if kind == "timeseries" else None
    data, _ = make_dataset(kind, effects, seed=22, n=n)
    result = report(diagnose(data))
    assert "outliers" not in [w["code"] for w in result["warnings"]]
    assert result["n"] == data.n


def test_a_residual_spike_under_a_smooth_force_is_the_models_not_a_glitch_of_f():
    # in a time series the prediction runs through x and t: a glitch there spikes the
    # residual while the measured force stays smooth, and replacing F would mend nothing
    rng = np.random.default_rng(6)
    n = 5_000
    force = 10.0 + 0.001 * np.arange(n) + 0.05 * rng.standard_normal(n)
    prediction = force - 0.05 * rng.standard_normal(n)
    prediction[2500] -= 2.0  # the model's spike
    residual = force - prediction
    rows = [np.arange(n)]
    assert np.flatnonzero(find_spikes(residual, rows)[0]).tolist() == [2500]
    assert not find_spikes(residual, rows, measured=force)[0].any()
    spiky = force.copy()
    spiky[1200] += 2.0  # the force's own spike
    found = find_spikes(spiky - prediction, rows, measured=spiky)[0]
    assert np.flatnonzero(found).tolist() == [1200]
