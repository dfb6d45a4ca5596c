"""Pydantic models of the fit endpoints."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, ConfigDict


class ModelFit(BaseModel):
    params: dict[str, float | None]
    stderr: dict[str, float | None]
    determined: dict[str, bool]
    rmse: float | None
    bic: float | None


class Covariance(BaseModel):
    names: list[str]
    matrix: list[list[float]]


class FinalFit(ModelFit):
    covariance: Covariance | None = None


class FitStep(ModelFit):
    effect: str
    evidence: str
    heldout: float | None


class HeldOut(BaseModel):
    before: float | None
    after: float | None


class Warning(BaseModel):
    code: str
    parameter: str | None
    message: str


class Structure(BaseModel):
    against: str
    strength: float


class CandidateVerdict(BaseModel):
    rmse: float | None
    bic: float | None
    heldout: float | None
    accepted: bool
    reason: str | None


class FitReport(BaseModel):
    """The identification report."""

    model_config = ConfigDict(extra="allow")

    kind: Literal["timeseries", "steady", "breakaway"]
    n: int
    noise_floor: float | None
    #: what the resolution of x adds to the prediction error through the fitted model [N]
    input_floor: float | None = None
    base: ModelFit
    steps: list[FitStep]
    effects: list[str]
    final: FinalFit
    error_before: float | None
    error_after: float | None
    heldout: HeldOut
    residual_white: bool
    unexplained: bool
    warnings: list[Warning]
    residual_structure: list[Structure]
    candidates: dict[str, CandidateVerdict]


class FitJobStatus(BaseModel):
    id: str
    source: str
    status: Literal["queued", "running", "done", "error", "cancelled"]
    progress: float
    message: str
    error: str | None = None
    report: FitReport | None = None
    series: dict | None = None


class SampleInfo(BaseModel):
    name: str
    title: str
    kind: Literal["timeseries", "steady", "breakaway"]
    description: str
    quiz: bool = False
