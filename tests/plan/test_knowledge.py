"""What a plan starts from: a report's values, covariance and open ranges; bad reports
are refused naming the key."""

import copy
import math

import numpy as np
import pytest

from breakaway.plan.knowledge import PlanError, from_params, from_report

from .records import high_rates, steady, timeseries


def test_a_report_with_every_parameter_determined_keeps_its_covariance():
    _, report = timeseries()
    knowledge = from_report(report)
    names, matrix = knowledge.covariance
    assert set(names) == {"Fc", "Fs", "V", "delta", "s"}
    for i, name in enumerate(names):
        assert math.sqrt(matrix[i][i]) == pytest.approx(report["final"]["stderr"][name], rel=1e-12)
    assert knowledge.ranges == {}
    assert knowledge.given == {"sigma": "no viscous effect in the model",
                               "n": "the viscous term is linear"}


def test_ramps_at_high_rates_leave_the_drop_below_the_slowest_breakaway_speed():
    _, report = high_rates()
    knowledge = from_report(report)
    slowest = report["extent"]["speeds"][0]
    assert knowledge.determined["Fc"] and not knowledge.determined["V"]
    # the level seen is Fc (determined): the drop is over below the slowest speed
    (low, high), = knowledge.ranges["V"]
    assert high == pytest.approx(0.5 * slowest) and low == pytest.approx(0.005 * slowest)
    assert knowledge.ranges["delta"] == [(0.5, 2.0)]
    (floor, top), = knowledge.ranges["Fs"]
    assert floor >= report["final"]["params"]["Fc"] and top == pytest.approx(
        floor + report["final"]["params"]["Fc"])
    assert knowledge.given["s"].startswith("the presliding scale the break-away record")


def test_a_level_nobody_determines_leaves_the_drop_on_either_side():
    _, report = high_rates()
    report = copy.deepcopy(report)
    report["final"]["determined"]["Fc"] = False
    report["final"]["stderr"]["Fc"] = None
    pieces = from_report(report).ranges["V"]
    slowest, fastest = report["extent"]["speeds"]
    assert len(pieces) == 2
    assert pieces[0][1] < slowest and pieces[1][0] > fastest


def test_a_loose_parameter_is_taken_two_standard_errors_either_side():
    _, report = steady()
    report = copy.deepcopy(report)
    V, se = report["final"]["params"]["V"], 0.3 * report["final"]["params"]["V"]
    report["final"]["determined"]["V"], report["final"]["stderr"]["V"] = False, se
    knowledge = from_report(report)
    (low, high), = knowledge.ranges["V"]
    assert low == pytest.approx(V * math.exp(-0.6)) and high == pytest.approx(V * math.exp(0.6))
    assert "too loosely" in knowledge.why_open["V"]


def test_a_report_without_covariance_is_taken_as_uncorrelated_and_says_so():
    _, report = timeseries()
    report = copy.deepcopy(report)
    del report["final"]["covariance"]
    knowledge = from_report(report)
    names, matrix = knowledge.covariance
    assert np.count_nonzero(np.asarray(matrix) - np.diag(np.diag(matrix))) == 0
    assert any("no covariance" in note for note in knowledge.notes)


def test_the_record_noise_is_its_scatter_about_the_fit_where_the_residual_is_white():
    _, report = high_rates()
    assert report["residual_white"]
    n, p = report["n"], len(report["final"]["params"])
    expected = report["final"]["rmse"] * math.sqrt(n / (n - p))
    assert from_report(report).noise == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("change, path", [
    (lambda r: r.pop("final"), ("report", "final", "params")),
    (lambda r: r["final"]["params"].pop("V"), ("report", "final", "params", "V")),
    (lambda r: r["final"]["params"].update(Fs=0.5), ("report", "final", "params", "Fs")),
    (lambda r: r["final"]["params"].update(delta="x"), ("report", "final", "params", "delta")),
    (lambda r: r.update(kind="other"), ("report", "kind")),
    (lambda r: r.update(effects=[1]), ("report", "effects")),
    (lambda r: r["final"]["covariance"].update(matrix=[[1.0]]), ("report", "final", "covariance")),
])
def test_bad_reports_are_refused_naming_the_key(change, path):
    _, report = timeseries()
    report = copy.deepcopy(report)
    change(report)
    with pytest.raises(PlanError) as caught:
        from_report(report)
    assert caught.value.path == path


def test_ranges_given_open_a_parameter_and_are_checked():
    knowledge = from_params({"Fc": 1.0, "Fs": 1.5}, ranges={"V": (1.0, 10.0)})
    assert knowledge.ranges == {"V": [(1.0, 10.0)]}
    with pytest.raises(PlanError) as caught:
        from_params({}, ranges={"V": (10.0, 1.0)})
    assert caught.value.path == ("ranges", "V")
    with pytest.raises(PlanError) as caught:
        from_params({}, ranges={"mass": (1.0, 2.0)})
    assert caught.value.path == ("ranges", "mass")
