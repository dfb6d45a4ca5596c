"""What to measure next: the experiment that determines what the data do not.

Given a model — an identification report (its parameters, their covariance, what the
record leaves open, its noise and extent) or a set of parameters — and the rig's
limits, the planner proposes the runs of one measurement family that minimise the
predicted uncertainty of the targets (by default the parameters the data do not
determine), predicts each parameter's standard error before and after, and writes the
programme a rig runs:

- ``ramps``: force ramps ``u = k·t`` from rest at chosen rates, each measuring the
  break-away force F_ba(k) of (E13); programme ``run,t,u``.
- ``steady``: constant-speed set-points in both directions, measuring F(v) of (E2);
  programme ``run,v``.
- ``sine``: one position sine through presliding and reversals, F recorded along it
  (E6'); programme ``t,x``.

A parameter the data do not determine has no value to design at: the plan holds over
the range the data leave open (the information averaged over a few values across it)
and gives its predicted standard errors at each. Where no run of the family within
the limits determines a target, the plan says so, says why, and names the family that
would.

>>> from breakaway.plan import plan_experiment
>>> plan = plan_experiment("ramps", report=report, limits={"u_max": 3.0})  # doctest: +SKIP
"""

from __future__ import annotations

from .knowledge import PlanError
from .planner import FAMILIES, plan_experiment
from .simulate import join, joint_fit, run_design

__all__ = ["FAMILIES", "PlanError", "join", "joint_fit", "plan_experiment", "run_design"]
