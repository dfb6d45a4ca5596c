"""Pydantic models of ``POST /api/plan`` (what to measure next)."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import AfterValidator, BaseModel, Field, model_validator

from ..params import DEFAULTS
from ..plan.curve import PARAMETERS
from ..settings import get_settings
from .schemas import _STRICT, Delta, FHat, NonNegative, Positive, _field_error

Parameter = Literal[PARAMETERS]


def _capped(field: str, setting: str):
    """A validator keeping ``field`` at most the server's setting ``setting``."""
    def check(value: int) -> int:
        cap = getattr(get_settings(), setting)
        if value > cap:
            raise ValueError(f"{field} must be <= {cap}, got {value}")
        return value
    return AfterValidator(check)


class PlanParams(BaseModel):
    """Model parameters to plan for when there is no report (the explorer's); omitted
    ones take ``breakaway.params.DEFAULTS``. Nothing is determined without data."""

    model_config = _STRICT

    Fc: Positive = Field(DEFAULTS["Fc"], description="Coulomb level [N]")
    Fs: Positive = Field(DEFAULTS["Fs"], description="Stribeck level [N], >= Fc")
    V: Positive = Field(DEFAULTS["V"], description="Stribeck velocity [m/s]")
    delta: Delta = Field(DEFAULTS["delta"], description="shape exponent, |δ| ≥ 0.05")
    sigma: NonNegative = Field(DEFAULTS["sigma"], description="viscous coefficient [N·s/m]")
    s: Positive = Field(DEFAULTS["s"], description="presliding scale [1/m]")
    z_ba: Positive = Field(DEFAULTS["z_ba"], lt=1, description="break-away fraction z*")
    F_hat: FHat = Field(DEFAULTS["F_hat"], description="level F̂ of (E12) for ramps")
    m: Positive | None = Field(None, description="moving mass [kg] (not used by the plan)")


class PlanLimits(BaseModel):
    """The rig's limits, in the record's units; an omitted one is taken from the record
    (the largest force and speed it reached, its travel, length and sampling rate) or,
    without a record, assumed (the answer's notes say which)."""

    model_config = _STRICT

    u_max: Positive | None = Field(None, description="largest force the rig applies [N]")
    v_max: Positive | None = Field(None, description="largest speed it reaches or measures [m/s]")
    v_min: Positive | None = Field(None, description="slowest speed it holds steadily [m/s]")
    travel: Positive | None = Field(None, description="its travel, peak to peak [m]")
    duration: Positive | None = Field(None, description="the longest one run may last [s]")
    sample_rate: Positive | None = Field(None, description="samples per second of a record [Hz]")


Range = Annotated[list[Annotated[float, Field(ge=0, json_schema_extra={"maximum": 1e30})]],
                  Field(min_length=2, max_length=2)]


class PlanRequest(BaseModel):
    """A model (a report, or parameters), the family of runs, the rig's limits, and
    what to determine."""

    model_config = _STRICT

    report: dict[str, Any] | None = Field(
        None, description="an identification report (POST /api/fit, breakaway fit --json)")
    params: PlanParams | None = Field(None, description="parameters instead of a report")
    family: Literal["ramps", "steady", "sine"] = Field(
        description="ramps: force ramps at chosen rates (break-away forces, E13); steady: "
                    "speed set-points in both directions (E2); sine: one position sine "
                    "through presliding and reversals (E6')")
    limits: PlanLimits | None = Field(None, description="the rig's limits")
    runs: Annotated[int, Field(ge=1), _capped("runs", "max_plan_runs")] | None = Field(
        None, description="runs of the plan (ramps, set-points; capped); default 12")
    noise: Positive | None = Field(None, description="std of one measured force [N]; "
                                   "default: the record's")
    targets: list[Parameter] | None = Field(
        None, max_length=len(PARAMETERS),
        description="parameters to determine; default: those the data do not")
    ranges: dict[Parameter, Range] | None = Field(
        None, description="{name: [low, high]}: take a parameter as open over this range")
    grid: Annotated[int, Field(ge=4), _capped("grid", "max_plan_grid")] | None = Field(
        None, description="candidate design points (capped)")

    @model_validator(mode="after")
    def _one_model(self) -> PlanRequest:
        if (self.report is None) == (self.params is None):
            raise _field_error("report", None, "give either a report or params, not both "
                               "and not neither", ("report",))
        return self


class Across(BaseModel):
    value: float
    stderr_after: float | None
    determined_after: bool


class Predicted(BaseModel):
    stderr_now: float | None = Field(description="standard error the data give now")
    stderr_after: float | None = Field(description="predicted after the plan (at the middle "
                                       "of an open range)")
    determined_now: bool
    determined_after: bool = Field(description="determined after the plan (over the whole "
                                   "range, for an open parameter)")
    target: bool
    range: list[float] | None = Field(None, description="the range an open parameter is "
                                      "taken over")
    pieces: list[list[float]] | None = Field(None, description="its pieces, when it may lie "
                                             "on either side of the data")
    why_open: str | None = None
    across: list[Across] | None = Field(None, description="predicted at values across the range")


class PlanResponse(BaseModel):
    """The proposed experiment."""

    family: Literal["ramps", "steady", "sine"]
    targets: list[str] = Field(description="the parameters the design is for")
    design: dict[str, Any] | None = Field(description="the runs (null: nothing to run)")
    predicted: dict[str, Predicted]
    programme: str = Field(description="CSV a rig runs: run,t,u (ramps), run,v (set-points), "
                           "t,x (sine); units in the comment lines")
    notes: list[str] = Field(description="what was assumed, what is left open and why")
    limits: dict[str, float | None]
    noise: float
    units: dict[str, str]
    seconds: float
