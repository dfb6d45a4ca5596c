"""``breakaway plan``: a report's plan as text or JSON, the programme to a file, and
bad input as one line with exit code 2."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from breakaway.cli import main
from breakaway.plan.checks import _ramps_record
from breakaway.identify import identify


@pytest.fixture(scope="module")
def report_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("plan") / "report.json"
    path.write_text(json.dumps(identify(_ramps_record(1, 40.0, 300.0, 0.005))))
    return path


def test_plan_prints_the_design_the_errors_and_the_notes(report_file, tmp_path, capsys):
    programme = tmp_path / "ramps.csv"
    assert main(["plan", str(report_file), "--family", "ramps", "--u-max", "3",
                 "--runs", "8", "-o", str(programme)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("breakaway plan: ramps, to determine Fs, V, δ")
    assert "8 force ramps from rest at k [N/s]" in out
    assert "predicted standard errors:" in out and "no -> yes  (target)" in out
    assert f"written to {programme}" in out
    text = programme.read_text()
    assert "\nrun,t,u\n" in text and text.count("\n8,") == 11


def test_plan_json_is_the_api_answer(report_file, capsys):
    assert main(["plan", str(report_file), "--family", "steady", "--targets", "V,delta",
                 "--v-min", "1", "--u-max", "3", "--json"]) == 0
    plan = json.loads(capsys.readouterr().out)
    assert plan["targets"] == ["V", "delta"] and plan["limits"]["v_min"] == 1.0
    assert plan["programme"].splitlines()[2] == "run,v"


def test_plan_for_parameters_with_a_range(capsys):
    assert main(["plan", "--params", '{"Fc": 1, "Fs": 1.5, "V": 10}', "--family", "sine",
                 "--range", "s=0.5:2", "--json"]) == 0
    plan = json.loads(capsys.readouterr().out)
    assert plan["predicted"]["s"]["range"] == [0.5, 2.0]


@pytest.mark.parametrize("args, message", [
    (["plan", "missing.json", "--family", "ramps"], "missing.json: cannot read"),
    (["plan", "--params", "[1]", "--family", "ramps"], "--params must be a JSON object"),
    (["plan", "--params", '{"Fs": 0.5}', "--family", "ramps"], "params.Fs: Fs must be >= Fc"),
    (["plan", "--params", "{}", "--family", "ramps", "--u-max", "-1"], "limits.u_max"),
    (["plan", "--family", "ramps"], "give a REPORT.json or --params JSON"),
])
def test_bad_input_is_one_line_and_exit_code_2(args, message):
    done = subprocess.run([sys.executable, "-m", "breakaway", *args], capture_output=True,
                          text=True)
    assert done.returncode == 2
    assert message in done.stderr and "Traceback" not in done.stderr
    assert done.stderr.count("\n") == 1
