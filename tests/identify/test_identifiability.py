"""What a fit determines: a parameter that is not determined only because it moves with
another says which combination of the two the data do determine, with the correlation,
in the data's units."""

from __future__ import annotations

import math
import re

import pytest

from breakaway.identify import identify, parse_csv
from breakaway.identify.fitting import fit_model, fit_with_effect
from breakaway.identify.report import correlated
from breakaway.identify.warnings.fit import fit_warnings

from . import machines


@pytest.fixture(scope="module")
def joint_in_degrees():
    return identify(parse_csv(machines.joint_in_degrees(2, command="ramp").csv.encode()))


@pytest.fixture(scope="module")
def with_its_drop():
    """The same joint's inertia fit with its Stribeck drop kept (the report takes the
    drop out: it is not resolved): there the presliding scale s moves with Fs."""
    fit = fit_with_effect(*_joint(), "inertia")
    return {"correlated": {"final": correlated(fit)},
            "final": {"params": fit.params, "stderr": fit.stderr,
                      "determined": fit.determined},
            "warnings": fit_warnings(fit)}


def _joint():
    data = parse_csv(machines.joint_in_degrees(2, command="ramp").csv.encode())
    return data, fit_model(data)


def test_a_correlated_parameter_names_the_combination_the_data_determine(with_its_drop):
    report = with_its_drop
    tied = report["correlated"]["final"]["s"]
    params, stderr = report["final"]["params"], report["final"]["stderr"]
    assert tied["with"] == "Fs" and abs(tied["r"]) > 0.99
    assert report["final"]["determined"]["s"] is False
    # s − c·Fs is known to σ_s·√(1 − r²): far tighter than s alone
    assert tied["stderr"] == pytest.approx(stderr["s"] * math.sqrt(1 - tied["r"] ** 2), rel=1e-9)
    assert tied["stderr"] < 0.2 * stderr["s"]
    assert math.copysign(1, tied["slope"]) == math.copysign(1, tied["r"])
    combined = params["s"] - tied["slope"] * params["Fs"]
    [message] = [w["message"] for w in report["warnings"]
                 if w["code"] == "undetermined" and w["parameter"] == "s"]
    sign = "+" if tied["slope"] < 0 else "−"
    assert f"moves with Fs (correlation r = {tied['r']:+.3f})" in message
    assert f"the data determine s {sign} {abs(tied['slope']):.3g}·Fs = {combined:.4g} 1/deg" in message
    assert message.startswith(f"s = {params['s']:.4g} 1/deg")


def test_every_value_in_a_rotary_reports_words_carries_its_unit(joint_in_degrees):
    report = joint_in_degrees
    assert report["units"]["F"] == "N·m" and report["units"]["x"] == "deg"
    texts = [w["message"] for w in report["warnings"]] + [s["evidence"] for s in report["steps"]]
    # a parameter quoted with a number is followed by its unit in the data's units
    for text in texts:
        for name, unit in report["units"].items():
            if unit in ("", "-", "s") or not re.search(rf"(?<![\w·]){re.escape(name)} = [-\d.e+]+", text):
                continue
            for quoted in re.finditer(rf"(?<![\w·]){re.escape(name)} = ([-\d.e+]+)( \S+)?", text):
                assert quoted.group(2) and quoted.group(2).strip(" ,;:)") == unit, (name, text)


def test_a_power_laws_scale_and_exponent_do_not_make_each_other_undetermined():
    # speeds of 5–500 (σ is the curve's value at the unit speed): σ and n move together
    # with a correlation above 0.99, which referring σ to a speed inside the data would
    # make zero; n and σ are determined by their own standard errors
    import numpy as np

    rng = np.random.default_rng(1)
    speeds = np.geomspace(5.0, 500.0, 15)
    v = np.concatenate([speeds, -speeds])
    F = np.sign(v) * (2.0 + 0.5 * np.abs(v) ** 0.5) + 0.01 * rng.standard_normal(v.size)
    lines = ["v [m/s],F [N]"] + [f"{a:.6g},{b:.6f}" for a, b in zip(v, F)]
    data = parse_csv("\n".join(lines).encode())
    fit = fit_with_effect(data, fit_model(data), "viscous-power")
    a = fit.assessment
    r = a.correlation[a.names.index("n"), a.names.index("sigma")]
    assert abs(r) > 0.99
    assert fit.determined["n"] and fit.determined["sigma"]
    assert fit.params["n"] == pytest.approx(0.5, abs=4 * fit.stderr["n"])
    assert fit.params["sigma"] == pytest.approx(0.5, abs=4 * fit.stderr["sigma"])
