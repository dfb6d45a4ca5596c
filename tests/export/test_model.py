"""Reading a report for export: what is taken, what is left out and why, units, and
bad reports that name what is missing."""

from __future__ import annotations

import json

import pytest

from breakaway.export import LANGUAGES, ReportError, export_model, model_from_report

from .conftest import BASE, REPORTS, ROTARY_UNITS, report_of


def test_body_effects_are_taken_and_measurement_effects_left_out():
    model = model_from_report(REPORTS["all-body-effects"])
    assert model.effects == ("asymmetry", "drift", "viscous")
    assert model.left_out == (("offset", "a bias of the force sensor, not friction"),)
    assert (model.sigma, model.Fc_neg, model.Fs_neg, model.alpha, model.t_0) == (
        150.0, 8.0, 10.5, 0.05, 2.0)
    assert model.n == 1.0


def test_effects_not_accepted_take_their_neutral_values():
    model = model_from_report(report_of({**BASE, "sigma": 99.0}))  # in params, not accepted
    assert model.sigma == 0.0 and model.n == 1.0 and model.alpha == 0.0
    assert model.levels_negative == (BASE["Fc"], BASE["Fs"])


def test_json_export_carries_parameters_effects_units_and_t0():
    document = json.loads(export_model(REPORTS["all-body-effects"], "json"))
    assert document["params"] == {**BASE, "sigma": 150.0, "n": 1.0, "Fc_neg": 8.0,
                                  "Fs_neg": 10.5, "alpha": 0.05, "t_0": 2.0}
    assert document["effects"] == ["asymmetry", "drift", "viscous"]
    assert document["left_out"] == [{"effect": "offset",
                                     "reason": "a bias of the force sensor, not friction"}]
    assert document["units"]["sigma"] == "N·s/m" and document["units"]["x"] == "m"
    assert document["t_0"] == 2.0


def test_rotary_units_reach_the_comments():
    report = REPORTS["viscous-power-rotary"]
    python, c = export_model(report, "python"), export_model(report, "c")
    assert "x [rad], v [rad/s], t [s], F [N·m] (rotary" in python
    assert "SIGMA = 4000.0  # viscous coefficient (0: none) [N·m·s/rad]" in python
    assert "BK_SIGMA = 4000.0; /* viscous coefficient (0: none) [N*m*s/rad] */" in c
    assert c.isascii()
    units = dict(ROTARY_UNITS)
    del units["Fc"]  # a report without a key's unit: the rotary default
    model = model_from_report(report_of(BASE, units=units))
    assert model.units["Fc"] == "N·m" and model.rotary


def test_equations_are_named_in_every_file():
    for lang in LANGUAGES:
        text = export_model(REPORTS["base"], lang)
        for number in ("(E2)", "(E4)", "(E6')"):
            assert number in text


def test_a_steady_report_needs_a_presliding_scale():
    report = report_of({k: BASE[k] for k in ("Fc", "Fs", "V", "delta")}, kind="steady")
    with pytest.raises(ReportError, match="report \\(steady\\) has no presliding scale s") as err:
        model_from_report(report)
    assert err.value.path == ("final", "params", "s")
    assert model_from_report(report, s=500.0).s == 500.0


def test_a_breakaway_report_uses_the_scale_its_fit_used():
    report = report_of({k: BASE[k] for k in ("Fc", "Fs", "V", "delta")}, kind="breakaway")
    report["s"] = 250.0
    assert model_from_report(report).s == 250.0


def test_drift_needs_t0():
    report = report_of({**BASE, "alpha": 0.01}, ("drift",), t_0=None)
    with pytest.raises(ReportError, match="effect drift needs t_0"):
        model_from_report(report)
    assert model_from_report(report, t_0=3.0).t_0 == 3.0


@pytest.mark.parametrize("report,message,path", [
    ([1, 2], "a report must be a JSON object", ()),
    ({"effects": []}, "report has no final.params", ("final", "params")),
    ({"final": {"params": BASE}}, "report has no effects list", ("effects",)),
    (report_of({k: v for k, v in BASE.items() if k != "V"}), "final.params lack V",
     ("final", "params", "V")),
    (report_of({**BASE, "delta": None}), "final.params.delta must be a number, got None",
     ("final", "params", "delta")),
    (report_of({**BASE, "Fc": "ten"}), "must be a number, got 'ten'", ("final", "params", "Fc")),
    (report_of({**BASE, "Fs": 5.0}), "Fs must be >= Fc", ("final", "params", "Fs")),
    (report_of({**BASE, "s": -1.0}), "s must be > 0", ("final", "params", "s")),
    (report_of(BASE, ("asymmetry",)), "effect asymmetry is accepted but report's "
     "final.params lack Fc_neg", ("final", "params", "Fc_neg")),
    (report_of({**BASE, "Fc_neg": 3.0, "Fs_neg": 2.0}, ("asymmetry",)),
     "Fs_neg must be >= Fc_neg", ("final", "params", "Fs_neg")),
    (report_of({**BASE, "sigma": 1.0, "n": 2.0}, ("viscous", "viscous-power")),
     "both viscous and viscous-power", ("effects",)),
    (report_of({**BASE, "sigma": 1.0}, ("viscous-power",)), "lack n", ("final", "params", "n")),
])
def test_bad_reports_name_what_is_missing(report, message, path):
    with pytest.raises(ReportError, match=message) as err:
        export_model(report, "c")
    assert err.value.path == path


def test_unknown_effects_are_named_as_left_out():
    model = model_from_report(report_of(BASE, ("wobble",)))
    assert model.left_out == (("wobble", "not an effect this version knows; not exported"),)
    assert "Left out: wobble" in export_model(report_of(BASE, ("wobble",)), "python")


def test_unknown_language():
    with pytest.raises(ValueError, match="lang must be one of python, c, json"):
        export_model(REPORTS["base"], "rust")
