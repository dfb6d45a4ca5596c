"""The command line: ``breakaway fit`` (human and JSON) and its errors."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from breakaway.cli import main
from breakaway.identify.synthetic import make_dataset, to_csv


@pytest.fixture
def steady_file(tmp_path):
    data, _ = make_dataset("steady", ("viscous",), seed=3)
    path = tmp_path / "steady.csv"
    path.write_text(to_csv(data))
    return path


def test_fit_prints_a_readable_report(steady_file, capsys):
    assert main(["fit", str(steady_file)]) == 0
    out = capsys.readouterr().out
    assert "effects found: viscous" in out
    assert "held-out" in out and "noise floor" in out
    assert "sigma" in out


def test_fit_json_is_the_report(steady_file, capsys):
    assert main(["fit", str(steady_file), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert report["effects"] == ["viscous"]
    assert report["error_after"] < report["error_before"]


def test_bad_file_exits_2_with_a_message_and_no_traceback(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t,x,F\n" + "".join(f"{i},0,{'x' if i == 5 else 1}\n" for i in range(12)))
    run = subprocess.run([sys.executable, "-m", "breakaway", "fit", str(bad)],
                         capture_output=True, text=True)
    assert run.returncode == 2
    assert "line 7, column 'F': 'x' is not a number" in run.stderr
    assert "Traceback" not in run.stderr


def test_missing_file(tmp_path, capsys):
    assert main(["fit", str(tmp_path / "none.csv")]) == 2
    assert "cannot read" in capsys.readouterr().err


def test_kind_option(steady_file, capsys):
    assert main(["fit", str(steady_file), "--kind", "breakaway"]) == 2
    assert "missing column" in capsys.readouterr().err


def test_long_fits_print_a_progress_line(steady_file, capsys, monkeypatch):
    import breakaway.cli as cli

    monkeypatch.setattr(cli, "PROGRESS_ROWS", 10)
    assert main(["fit", str(steady_file)]) == 0
    err = capsys.readouterr().err
    assert "breakaway fit:   0 % fitting the base model" in err
    assert "100 % done" in err


def test_text_report_lists_warnings_and_undetermined_parameters(tmp_path, capsys):
    import numpy as np

    k = np.full(20, 5.0)
    F = 1.2 + 0.01 * np.random.default_rng(0).standard_normal(20)
    path = tmp_path / "one-rate.csv"
    path.write_text("k,F_ba\n" + "".join(f"{a},{b}\n" for a, b in zip(k, F)))
    assert main(["fit", str(path)]) == 0
    out = capsys.readouterr().out
    assert "[single-rate]" in out
    assert "(not determined by the data)" in out
    assert "candidates not accepted:" in out


def test_a_sentence_said_of_several_parameters_is_printed_once_naming_them():
    from breakaway.identify.text import _grouped

    warnings = [{"code": "beyond-data", "parameter": "V", "message": "the drop is unknown"},
                {"code": "beyond-data", "parameter": "delta", "message": "the drop is unknown"},
                {"code": "beyond-data", "parameter": "Fs", "message": "Fs is above"},
                {"code": "quantised", "parameter": "x", "message": "the drop is unknown"}]
    assert _grouped(warnings) == [("beyond-data", "the drop is unknown", ["V", "delta"]),
                                  ("beyond-data", "Fs is above", ["Fs"]),
                                  ("quantised", "the drop is unknown", ["x"])]


def test_several_files_give_one_summary_row_each(tmp_path, capsys):
    import csv

    paths = []
    for name, (kind, effects) in {"a": ("steady", ("viscous",)),
                                  "b": ("breakaway", ("dwell",))}.items():
        data, _ = make_dataset(kind, effects, seed=3)
        path = tmp_path / f"{name}.csv"
        path.write_text(to_csv(data))
        paths.append(str(path))
    bad = tmp_path / "bad.csv"
    bad.write_text("v,F\n1,2\n")
    paths.append(str(bad))
    prefix = tmp_path / "summary"
    assert main(["fit", *paths, "--jobs", "2", "--summary", str(prefix)]) == 2
    assert "bad.csv" in capsys.readouterr().err
    rows = list(csv.DictReader(open(f"{prefix}.csv", encoding="utf-8")))
    assert [row["file"] for row in rows] == paths
    assert rows[0]["effects"] == "viscous" and rows[1]["effects"] == "dwell"
    assert float(rows[0]["error_after"]) < float(rows[0]["error_before"])
    assert rows[2]["error"].startswith("only 1 data row")
    table = json.load(open(f"{prefix}.json", encoding="utf-8"))
    assert [t["effects"] for t in table[:2]] == ["viscous", "dwell"]
    assert table[0]["kind"] == "steady" and table[1]["rows"] == 120


def test_a_dask_cluster_gives_the_same_table_as_local_processes(tmp_path, capsys):
    from dask.distributed import LocalCluster

    paths = []
    for name, (kind, effects) in {"a": ("steady", ("viscous",)),
                                  "b": ("breakaway", ("dwell",))}.items():
        data, _ = make_dataset(kind, effects, seed=4)
        path = tmp_path / f"{name}.csv"
        path.write_text(to_csv(data))
        paths.append(str(path))
    paths.append(str(tmp_path / "missing.csv"))
    assert main(["fit", *paths, "--jobs", "2", "--summary", str(tmp_path / "local")]) == 2
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        code = main(["fit", *paths, "--dask", cluster.scheduler_address,
                     "--summary", str(tmp_path / "dask")])
    assert code == 2
    assert "missing.csv" in capsys.readouterr().err
    local = json.load(open(tmp_path / "local.json", encoding="utf-8"))
    remote = json.load(open(tmp_path / "dask.json", encoding="utf-8"))
    assert [row["file"] for row in remote] == paths
    assert [row["effects"] for row in remote] == ["viscous", "dwell", None]
    for mine, theirs in zip(local[:2], remote[:2]):
        assert theirs["error_after"] == pytest.approx(mine["error_after"], rel=1e-9)
        assert theirs["kind"] == mine["kind"] and theirs["rows"] == mine["rows"]
    assert remote[2]["error"].startswith("cannot read")


def test_dask_without_distributed_says_how_to_install(monkeypatch, tmp_path):
    import builtins

    real_import = builtins.__import__

    def no_dask(name, *args, **kwargs):
        if name.startswith("dask"):
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_dask)
    with pytest.raises(SystemExit, match=r"pip install 'breakaway\[dask\]'"):
        main(["fit", str(tmp_path / "a.csv"), "--dask", "tcp://127.0.0.1:1"])


# ---------------------------------------------------------------------------------
# breakaway export
# ---------------------------------------------------------------------------------


@pytest.fixture
def report_file(tmp_path):
    """A report of `breakaway fit --json` on a seeded steady file."""
    data, _ = make_dataset("steady", ("viscous",), seed=3)
    csv = tmp_path / "steady.csv"
    csv.write_text(to_csv(data))
    run = subprocess.run([sys.executable, "-m", "breakaway", "fit", str(csv), "--json"],
                         capture_output=True, text=True, check=True)
    path = tmp_path / "report.json"
    path.write_text(run.stdout)
    return path


def test_export_writes_the_module_a_steady_report_allows(report_file, tmp_path, capsys):
    out = tmp_path / "model.py"
    assert main(["export", str(report_file), "--lang", "python", "--s", "1000",
                 "-o", str(out)]) == 0
    namespace = {}
    exec(compile(out.read_text(), str(out), "exec"), namespace)
    sigma = json.loads(report_file.read_text())["final"]["params"]["sigma"]
    assert namespace["SIGMA"] == sigma and namespace["S"] == 1000.0
    assert namespace["steady"](0.0) == 0.0
    assert main(["export", str(report_file), "--lang", "json", "--s", "1000"]) == 0
    assert json.loads(capsys.readouterr().out)["params"]["sigma"] == sigma


@pytest.mark.parametrize("content,message", [
    (None, "cannot read: No such file or directory"),
    ("{not json", "not a JSON report"),
    ('{"effects": []}', "report has no final.params"),
])
def test_export_of_a_bad_report_exits_2_with_one_line(tmp_path, content, message):
    path = tmp_path / "report.json"
    if content is not None:
        path.write_text(content)
    run = subprocess.run([sys.executable, "-m", "breakaway", "export", str(path), "--lang", "c"],
                         capture_output=True, text=True)
    assert run.returncode == 2 and run.stdout == ""
    assert run.stderr.count("\n") == 1 and message in run.stderr
    assert "Traceback" not in run.stderr


def test_export_names_the_missing_scale_of_a_steady_report(report_file):
    run = subprocess.run([sys.executable, "-m", "breakaway", "export", str(report_file),
                          "--lang", "c"], capture_output=True, text=True)
    assert run.returncode == 2
    assert "has no presliding scale s" in run.stderr and "--s" in run.stderr
