"""What the §8 report of a machine-like recording must say, and the one check that
both the tests (:mod:`tests.identify.test_machines`) and the benchmark
(``benchmarks/realistic.py``) run on it.

An :class:`Expectation` is data: the effects the recording must name and those it may
name (any other is an effect that is not in the data), the warnings, which parameters
must (not) be determined, the values they must come within when determined, and the
forces and speeds the file reaches (no parameter is determined outside them).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

#: Force levels of the report: determined values must lie within the file's forces.
LEVELS = ("Fc", "Fs", "Fc_neg", "Fs_neg")


@dataclass(frozen=True)
class Close:
    """A parameter's true value and how close a determined report must come."""

    value: float
    rel: float | None = 0.10
    abs: float | None = None
    #: the report must determine it (else: checked only where it is determined)
    required: bool = False

    def admits(self, reported: float) -> bool:
        if self.abs is not None:
            return abs(reported - self.value) <= self.abs
        return abs(reported - self.value) <= self.rel * abs(self.value)

    def describe(self) -> str:
        tol = f"± {self.abs:g}" if self.abs is not None else f"± {100 * self.rel:.0f} %"
        return f"{self.value:.4g} {tol}"


@dataclass(frozen=True)
class Expectation:
    """What the report must say about one recording.

    Attributes
    ----------
    required : frozenset of str
        Effects that must be named.
    allowed : frozenset of str
        Effects that may be named (the required ones included): the physics the data
        hold. Any other named effect is not in the data.
    warnings : tuple of (code, parameter)
        Warnings that must be present; ``parameter`` None matches any.
    any_warnings : tuple of tuple of (code, parameter)
        Groups of warnings of which at least one must be present.
    determined : dict of str to bool
        Parameters of the final model that must be determined (True) or not (False);
        a parameter missing from the report counts as not determined.
    close : dict of str to Close
        Final values that must come within a tolerance of the truth.
    unexplained : bool or None
        The required ``unexplained`` flag (None: either).
    structure : tuple of str
        ``residual_structure`` must name one of these among its two strongest.
    lower_bound : tuple (parameter, value) or None
        A ``beyond-data`` warning on the parameter must give this bound (a number in its
        message within 3 % of it).
    refused : dict of str to str
        Candidates that must not be tried, and the start of the reason they give.
    noise : tuple (value, factor) or None
        The noise floor must lie within ``factor`` of ``value`` either way.
    force_max, speed_max : float
        The largest |force| and |speed| of the file: no level or Stribeck velocity is
        determined above them (10 % margin).
    input_floor : bool
        The report must carry ``input_floor`` (MODEL.md §8: the share of the prediction
        error that x's resolution sets), a finite number ≥ 0.
    beyond_speed : bool
        A Stribeck velocity the report gives above the fastest speed (10 % margin) must
        carry a ``beyond-data`` warning on V (MODEL.md §7b, 5).
    """

    required: frozenset = frozenset()
    allowed: frozenset = frozenset()
    warnings: tuple = ()
    any_warnings: tuple = ()
    determined: dict = field(default_factory=dict)
    close: dict = field(default_factory=dict)
    unexplained: bool | None = None
    structure: tuple = ()
    lower_bound: tuple | None = None
    refused: dict = field(default_factory=dict)
    noise: tuple | None = None
    force_max: float = math.inf
    speed_max: float = math.inf
    input_floor: bool = False
    beyond_speed: bool = False

    def summary(self) -> str:
        """One line: the effects and warnings expected."""
        effects = ", ".join(sorted(self.required)) or "none"
        extra = sorted(self.allowed - self.required)
        if extra:
            effects += f" (may: {', '.join(extra)})"
        codes = [f"{c}({p})" if p else c for c, p in self.warnings]
        codes += ["/".join(f"{c}({p})" if p else c for c, p in group)
                  for group in self.any_warnings]
        return effects + ("; " + ", ".join(codes) if codes else "")


def has_warning(report, code, parameter=None) -> bool:
    return any(w["code"] == code and (parameter is None or w["parameter"] == parameter)
               for w in report["warnings"])


def _numbers(text):
    return [float(m) for m in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", text)]


def failures(report: dict, expect: Expectation) -> list[str]:
    """Every way ``report`` falls short of ``expect`` (empty: it says what it must)."""
    out = []
    named = set(report["effects"])
    for effect in sorted(expect.required - named):
        verdict = report["candidates"].get(effect, {})
        out.append(f"{effect} not named ({verdict.get('reason')})")
    for effect in sorted(named - expect.allowed):
        out.append(f"{effect} named but not in the data")
    for code, parameter in expect.warnings:
        if not has_warning(report, code, parameter):
            out.append(f"no {code} warning" + (f" on {parameter}" if parameter else ""))
    for group in expect.any_warnings:
        if not any(has_warning(report, c, p) for c, p in group):
            out.append("none of the warnings " + ", ".join(f"{c}({p})" for c, p in group))
    final = report["final"]
    for name, wanted in expect.determined.items():
        got = bool(final["determined"].get(name, False))
        if got != wanted:
            value = final["params"].get(name)
            out.append(f"{name} = {value} {'not ' if wanted else ''}determined, "
                       f"expected {'' if wanted else 'not '}determined")
    for name, close in expect.close.items():
        value = final["params"].get(name)
        determined = bool(final["determined"].get(name, False))
        if close.required and not determined:
            out.append(f"{name} = {value} not determined (truth {close.value:.4g})")
        elif determined and not close.admits(value):
            out.append(f"{name} = {value:.4g}, expected {close.describe()}")
    if expect.unexplained is not None and report["unexplained"] != expect.unexplained:
        out.append(f"unexplained is {report['unexplained']}, expected {expect.unexplained}")
    if expect.structure:
        top = [s["against"] for s in report["residual_structure"][:2]]
        if not set(top) & set(expect.structure):
            out.append(f"residual_structure leads with {top}, expected one of "
                       f"{list(expect.structure)}")
    if expect.lower_bound is not None:
        name, bound = expect.lower_bound
        messages = [w["message"] for w in report["warnings"]
                    if w["code"] == "beyond-data" and w["parameter"] == name]
        if not any(abs(x - bound) <= 0.03 * bound for m in messages for x in _numbers(m)):
            out.append(f"no beyond-data message on {name} giving the bound {bound:.4g}")
    for effect, prefix in expect.refused.items():
        reason = report["candidates"].get(effect, {}).get("reason") or ""
        if not reason.startswith(prefix):
            out.append(f"{effect} not refused as {prefix} (reason: {reason or None})")
    if expect.noise is not None:
        value, factor = expect.noise
        floor = report["noise_floor"]
        if not value / factor <= floor <= value * factor:
            out.append(f"noise floor {floor:.3g}, expected {value:.3g} within {factor:g}x")
    if expect.input_floor:
        value = report.get("input_floor")
        if not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
            out.append(f"input_floor is {value!r}, expected a number ≥ 0")
    if expect.beyond_speed:
        V = final["params"].get("V")
        if V is not None and V > 1.1 * expect.speed_max and not has_warning(report, "beyond-data", "V"):
            out.append(f"V = {V:.4g} beyond the fastest speed {expect.speed_max:.4g} "
                       f"without a beyond-data warning")
    out += outside_data(final, expect)
    return out


def outside_data(final: dict, expect: Expectation) -> list[str]:
    """Determined levels above the file's largest force, or a determined Stribeck
    velocity above its largest speed: parameters of a part of the curve the data
    never show (MODEL.md §8 ``beyond-data``)."""
    out = []
    for name in LEVELS:
        value = final["params"].get(name)
        if final["determined"].get(name) and value is not None \
                and abs(value) > 1.1 * expect.force_max:
            out.append(f"{name} = {value:.4g} determined above the largest force "
                       f"{expect.force_max:.4g}")
    V = final["params"].get("V")
    if final["determined"].get("V") and V is not None and V > 1.1 * expect.speed_max:
        out.append(f"V = {V:.4g} determined above the largest speed {expect.speed_max:.4g}")
    return out


def verdict_params(families, seeds, known_gaps: dict):
    """pytest parameters ``(family, seed)`` for every family and each of its
    ``seeds(family)``, marked as a strict expected failure where ``known_gaps`` gives
    the reason (so that a change that mends one fails until its entry is removed)."""
    import pytest

    for family in families:
        for seed in seeds(family):
            gap = known_gaps.get((family, seed))
            marks = [pytest.mark.xfail(strict=True, reason=gap)] if gap else []
            yield pytest.param(family, seed, marks=marks, id=f"{family}-{seed}")
