"""The exported Python module and C file against the package's evaluation of the same
model and discretisation (breakaway.export.reference), to 1e-9 relative."""

from __future__ import annotations

import importlib.util
import math
import shutil
import subprocess

import numpy as np
import pytest

from breakaway.export import export_model, model_from_report, steady_force, streaming_force
from breakaway.presliding import presliding_force

from .conftest import BASE, REPORTS, report_of, trajectory

RTOL = 1e-9
DRIVER = r"""
#include <stdio.h>
#include <string.h>
#include "friction_model.c"

int main(int argc, char **argv)
{
    double a, b;
    bk_state s;
    if (argc > 1 && strcmp(argv[1], "steady") == 0) {
        while (scanf("%lf %lf", &a, &b) == 2)
            printf("%.17g %.17g\n", bk_steady(a), bk_steady_at(a, b));
        return 0;
    }
    bk_init(&s);
    while (scanf("%lf %lf", &a, &b) == 2)
        printf("%.17g\n", bk_step(&s, a, b));
    return 0;
}
"""


def close(got, want):
    """Equal to 1e-9 relative (of each value, or of the force scale where F ≈ 0)."""
    got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
    np.testing.assert_allclose(got, want, rtol=RTOL, atol=RTOL * 1e-3 * np.max(np.abs(want)))


def load_module(source, path):
    path.write_text(source)
    spec = importlib.util.spec_from_file_location(f"friction_model_{abs(hash(path))}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def compiler():
    cc = shutil.which("cc") or shutil.which("gcc")
    assert cc, "no C compiler (cc or gcc) on PATH: the C export cannot be tested"
    return cc


def build(cc, source, directory):
    (directory / "friction_model.c").write_text(source)
    (directory / "driver.c").write_text(DRIVER)
    # the exported file alone, as a user compiles it, with the strictest warnings ...
    for flags in (["-std=c99", "-Wall", "-Werror"],
                  ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-Werror"]):
        subprocess.run([cc, *flags, "-c", "friction_model.c", "-o", "friction_model.o"],
                       cwd=directory, check=True, capture_output=True, text=True)
    # ... and with a driver that prints what it computes
    subprocess.run([cc, "-std=c99", "-Wall", "-Werror", "-o", "driver", "driver.c", "-lm"],
                   cwd=directory, check=True, capture_output=True, text=True)
    return directory / "driver"


def run(program, rows, *args):
    text = "".join(" ".join(repr(float(value)) for value in row) + "\n" for row in rows)
    out = subprocess.run([str(program), *args], input=text, capture_output=True, text=True,
                         check=True).stdout
    return np.array([[float(value) for value in line.split()] for line in out.splitlines()])


@pytest.mark.parametrize("seed", [1, 2])
def test_python_step_reproduces_the_reference(report, seed, tmp_path):
    model = model_from_report(report)
    module = load_module(export_model(report, "python"), tmp_path / "friction_model.py")
    t, x = trajectory(seed)
    presliding = module.Presliding()
    got = [presliding.step(xi, ti) for xi, ti in zip(x, t)]
    close(got, streaming_force(model, t, x))
    assert got[0] == 0.0  # virgin


def test_python_steady_takes_floats_sequences_and_arrays(report, tmp_path):
    model = model_from_report(report)
    module = load_module(export_model(report, "python"), tmp_path / "friction_model.py")
    v = np.linspace(-4 * model.V, 4 * model.V, 101)
    want = steady_force(model, v)
    close([module.steady(float(value)) for value in v], want)
    close(module.steady(v.tolist()), want)
    array = module.steady(v.reshape(101, 1))
    assert isinstance(array, np.ndarray) and array.shape == (101, 1)
    close(array.ravel(), want)
    close(module.steady(v, 7.5), steady_force(model, v, 7.5))
    assert module.steady(0) == 0.0


@pytest.mark.parametrize("seed", [1, 2])
def test_c_step_and_steady_reproduce_the_reference(report, seed, compiler, tmp_path):
    model = model_from_report(report)
    program = build(compiler, export_model(report, "c"), tmp_path)
    t, x = trajectory(seed)
    F = run(program, zip(x, t))[:, 0]
    close(F, streaming_force(model, t, x))
    assert F[0] == 0.0
    v = np.linspace(-4 * model.V, 4 * model.V, 101)
    steady = run(program, zip(v, np.full(v.size, 7.5)), "steady")
    close(steady[:, 0], steady_force(model, v))
    close(steady[:, 1], steady_force(model, v, 7.5))


def test_time_must_increase(compiler, tmp_path):
    report = REPORTS["base"]
    module = load_module(export_model(report, "python"), tmp_path / "friction_model.py")
    presliding = module.Presliding()
    presliding.step(0.0, 1.0)
    with pytest.raises(ValueError, match="t must increase"):
        presliding.step(1e-4, 1.0)
    program = build(compiler, export_model(report, "c"), tmp_path)
    out = run(program, [(0.0, 1.0), (1e-4, 1.0), (1e-4, 1.1)])[:, 0]
    assert math.isnan(out[1]) and out[2] == pytest.approx(presliding.step(1e-4, 1.1), rel=RTOL)


def test_streaming_form_is_the_reference_discretisation_but_for_the_velocity():
    """On a finely sampled record the backward difference differs from MODEL.md §3's
    central one by half a sample: the forces agree to a small fraction of Fs."""
    t = np.linspace(0.0, 4.0, 40_001)
    x = 2e-3 * np.sin(2 * np.pi * 0.5 * t) + 2e-4 * np.sin(2 * np.pi * 3 * t)
    model = model_from_report(report_of(BASE))
    streamed = streaming_force(model, t, x)
    batch = presliding_force(t, x, BASE["Fc"], BASE["Fs"], BASE["V"], BASE["delta"], BASE["s"])
    assert np.max(np.abs(streamed - batch)) < 2e-3 * BASE["Fs"]
    assert np.max(np.abs(streamed - batch)) > 0  # not the same computation


@pytest.mark.parametrize("effect", ["viscous", "viscous-power"])
def test_an_identified_model_leaves_the_tool_unchanged(effect, compiler, tmp_path):
    """A report from the identification itself: its fitted model, exported, run."""
    from breakaway.identify import identify
    from breakaway.identify.synthetic import make_dataset

    data, _ = make_dataset("timeseries", (effect,), seed=4, n=3000)
    report = identify(data)
    assert report["effects"] == [effect] and report["t_0"] == data.columns["t"][0]
    model = model_from_report(report)
    fitted = report["final"]["params"]
    assert model.sigma == fitted["sigma"] and model.n == fitted.get("n", 1.0)
    t, x = data.columns["t"], data.columns["x"]
    want = streaming_force(model, t, x)
    module = load_module(export_model(report, "python"), tmp_path / "friction_model.py")
    presliding = module.Presliding()
    close([presliding.step(xi, ti) for xi, ti in zip(x, t)], want)
    program = build(compiler, export_model(report, "c"), tmp_path)
    close(run(program, zip(x, t))[:, 0], want)
