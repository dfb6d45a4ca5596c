"""The plan checked by simulation: a synthetic truth, a first record of it with seeded
noise, its report, the plan, the plan's runs simulated on the truth, and the refit on
both records. Over many seeds the refit's actual errors are set against the standard
errors the plan predicted (and the refit's own).

Four cases, each a function of the seed:

- :func:`open_drop`: break-away ramps only at high rates leave V and δ wholly open
  (and Fs beyond the data); the plan's ramps, refitted with the first record, must
  determine them with honest standard errors.
- :func:`loose_ramps`, :func:`loose_steady`: a first record (ramps across part of the
  drop; a steady curve with no speed below V) holds V loosely; the actual errors after
  the plan must match its predicted standard errors.
- :func:`sine_for_s`: a steady curve holds no presliding scale; a sine planned over the
  range s is believed to lie in must determine it as predicted.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..identify import identify
from ..identify.fitting import fit_model
from ..identify.synthetic import _dataset
from ..quasistatic import breakaway_force
from ..steady import steady_state_force
from .planner import plan_experiment
from .simulate import join, joint_fit, run_design

#: The note's Fig. 5 curve with V = 50 (s = 1: normalised units).
RAMP_TRUTH = {"Fc": 1.0, "Fs": 1.5, "V": 50.0, "delta": 1.0}
#: A steady curve of a small actuator (N, m/s) with a presliding distance of 0.5 mm.
STEADY_TRUTH = {"Fc": 10.0, "Fs": 15.0, "V": 0.005, "delta": 1.0, "s": 2000.0}


@dataclass
class Check:
    """One seed of a check: the truth, the first report, the plan and the refit."""

    truth: dict
    report: dict
    plan: dict
    refit: dict  # params, stderr, determined
    #: the parameter the check is about (V, s), and whether the first record holds it
    #: loosely (a standard error, or a range given): the plan then predicts its error
    #: at the estimate
    about: str = "V"
    held: bool = True

    def within(self, name: str, stderr: str = "predicted", spread: float = 2.0) -> bool | None:
        """Whether the refit's actual error of ``name`` is within ``spread`` standard
        errors: those the plan predicted, or the refit's own (``stderr="refit"``).
        None where there is none to compare with."""
        if stderr == "predicted":
            se = self.plan["predicted"][name]["stderr_after"]
        else:
            se = self.refit["stderr"].get(name)
        if se is None:
            return None
        return abs(self.refit["params"][name] - self.truth[name]) <= spread * se


def _ramps_record(seed: int, low: float, high: float, noise: float):
    rng = np.random.default_rng(seed)
    k = np.repeat(np.geomspace(low, high, 8), 3)
    F = breakaway_force(k, **RAMP_TRUTH) + noise * rng.standard_normal(k.size)
    return _dataset("breakaway", {"k": k, "F_ba": F}, {"s": "1.0"})


def _steady_record(seed: int, slowest: float, rows: int, noise: float):
    rng = np.random.default_rng(seed)
    speeds = np.geomspace(slowest, 0.05, rows)
    v = np.concatenate([-speeds[::-1], speeds])
    curve = [STEADY_TRUTH[name] for name in ("Fc", "Fs", "V", "delta")]
    F = steady_state_force(v, *curve) + noise * rng.standard_normal(v.size)
    return _dataset("steady", {"v": v, "F": F})


def _fitted(fit) -> dict:
    return {"params": dict(fit.params), "stderr": dict(fit.stderr),
            "determined": dict(fit.determined)}


def _loosely(report: dict, name: str) -> bool:
    return report["final"]["stderr"].get(name) is not None


def _ramps_check(seed: int, low: float, high: float, noise: float) -> Check:
    first = _ramps_record(seed, low, high, noise)
    report = identify(first)
    plan = plan_experiment("ramps", report=report, limits={"u_max": 3.0})
    new = run_design(plan["design"], RAMP_TRUTH, noise, seed + 1000)
    return Check(RAMP_TRUTH, report, plan, _fitted(fit_model(join(first, new))),
                 held=_loosely(report, "V"))


def open_drop(seed: int) -> Check:
    """Ramps at 40 to 300 N/s (break-away speeds 12 to 90 times V), σ = 0.005 N."""
    return _ramps_check(seed, 40.0, 300.0, 0.005)


def loose_ramps(seed: int) -> Check:
    """Ramps at 1.5 to 40 N/s (break-away speeds from half V up), σ = 0.01 N."""
    return _ramps_check(seed, 1.5, 40.0, 0.01)


def loose_steady(seed: int) -> Check:
    """A steady curve at 40 speeds each way from V to 10·V, σ = 0.05 N; the rig holds
    speeds down to V/20 for the plan's set-points."""
    noise = 0.05
    first = _steady_record(seed, STEADY_TRUTH["V"], 40, noise)
    report = identify(first)
    plan = plan_experiment("steady", report=report,
                           limits={"v_min": STEADY_TRUTH["V"] / 20, "u_max": 20.0})
    new = run_design(plan["design"], STEADY_TRUTH, noise, seed + 1000)
    return Check(STEADY_TRUTH, report, plan, _fitted(fit_model(join(first, new))),
                 held=_loosely(report, "V"))


#: The range the presliding scale is believed to lie in before the sine [1/m]
#: (presliding distances of 0.125 to 2 mm), centred on the truth on a log scale.
S_RANGE = (500.0, 8000.0)


def sine_for_s(seed: int) -> Check:
    """A steady curve at 30 speeds each way from 0.5 mm/s to 50 mm/s, σ = 0.05 N (it
    determines the curve, and holds nothing of s); a 5-s sine within 10 mm of travel
    planned for s over :data:`S_RANGE`; both records refitted together."""
    noise = 0.05
    first = _steady_record(seed, 5e-4, 30, noise)
    report = identify(first)
    plan = plan_experiment("sine", report=report, ranges={"s": S_RANGE},
                           limits={"travel": 0.01, "duration": 5.0, "u_max": 25.0})
    new = run_design(plan["design"], STEADY_TRUTH, noise, seed + 1000)
    start = {**report["final"]["params"], "s": float(np.sqrt(S_RANGE[0] * S_RANGE[1]))}
    return Check(STEADY_TRUTH, report, plan, joint_fit([first, new], start, [noise, noise]),
                 about="s")


def coverage(checks, name: str, stderr: str = "predicted") -> tuple[int, int]:
    """(hits, counted): how many of ``checks`` hold ``name``'s actual error within two
    standard errors, of those that give one; against the plan's prediction, only the
    checks whose first record holds ``name`` loosely (a plan made over a range the
    data leave wholly open predicts at the range's middle, not at the truth)."""
    if stderr == "predicted":
        checks = [c for c in checks if c.held or c.about != name]
    verdicts = [c.within(name, stderr) for c in checks]
    counted = [v for v in verdicts if v is not None]
    return sum(counted), len(counted)


__all__ = ["Check", "RAMP_TRUTH", "STEADY_TRUTH", "S_RANGE", "coverage", "loose_ramps",
           "loose_steady", "open_drop", "sine_for_s"]
