"""What a report carries for the plan of the next experiment: the covariance of the
parameters with a standard error, and the extent of the record."""

import numpy as np
import pytest

from breakaway.identify import identify
from breakaway.identify.synthetic import make_dataset


@pytest.mark.parametrize("kind", ["steady", "breakaway"])
def test_covariance_has_the_standard_errors_on_its_diagonal(kind):
    data, _ = make_dataset(kind, seed=2)
    report = identify(data)
    final = report["final"]
    cov = final["covariance"]
    names = [n for n, se in final["stderr"].items() if se is not None]
    assert cov["names"] == names
    matrix = np.asarray(cov["matrix"])
    np.testing.assert_allclose(np.sqrt(np.diag(matrix)), [final["stderr"][n] for n in names],
                               rtol=1e-12)
    np.testing.assert_allclose(matrix, matrix.T)
    assert np.all(np.linalg.eigvalsh(matrix) > -1e-12 * np.max(np.diag(matrix)))


def test_extent_of_a_steady_curve():
    data, _ = make_dataset("steady", seed=1)
    extent = identify(data)["extent"]
    v, F = data.columns["v"], data.columns["F"]
    assert extent["force"] == pytest.approx(np.max(np.abs(F)))
    assert extent["speed"] == pytest.approx(np.max(np.abs(v)))
    assert extent["speeds"] == pytest.approx([np.min(np.abs(v)), np.max(np.abs(v))])


def test_extent_of_break_away_data_is_in_break_away_speeds():
    data, _ = make_dataset("breakaway", seed=1)
    report = identify(data)
    extent = report["extent"]
    k = data.columns["k"]
    assert extent["rates"] == [k.min(), k.max()]
    p = report["final"]["params"]
    level = p["Fc"] + (p["Fs"] - p["Fc"]) / 2
    # E12 at z* = 0.95 with s = 1 and F̂ = avg
    assert extent["speed"] == pytest.approx(k.max() / (level * -np.log(0.95)), rel=1e-9)


def test_extent_of_a_time_series():
    data, _ = make_dataset("timeseries", seed=0, n=3000)
    extent = identify(data)["extent"]
    t, x = data.columns["t"], data.columns["x"]
    assert extent["travel"] == pytest.approx(np.ptp(x))
    assert extent["duration"] == pytest.approx(t[-1] - t[0])
    assert extent["sample_rate"] == pytest.approx(1000.0)
