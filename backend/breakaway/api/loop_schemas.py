"""Pydantic models of ``POST /api/loop``: the position loop.

The plant's fields are those of the other simulations (:class:`~.schemas.PlantRequest`);
the controller, reference and compensation are objects of their own. Every omitted
value takes ``breakaway.params.LOOP_DEFAULTS`` (per model) or ``LOOP_COMMON``.
"""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import AfterValidator, BaseModel, Field, model_validator

from ..params import LOOP_COMMON, LOOP_DEFAULTS
from ..settings import get_settings
from .schemas import (_STRICT, Delta, FHat, Floats, GridSize, Magnitude, NonNegative,
                      PlantRequest, Positive, _field_error)

#: Sine periods a run may hold at most (more is not a plot, only a long wait).
MAX_SINE_PERIODS = 200


def _non_zero(value: float | None) -> float | None:
    if value == 0:
        raise ValueError("must be non-zero")
    return value


def _cap_duration(value: float) -> float:
    cap = get_settings().loop_max_duration
    if value > cap:
        raise ValueError(f"duration must be <= {cap:g} s, got {value:g}")
    return value


NonZero = Annotated[float, AfterValidator(_non_zero), Magnitude]
Duration = Annotated[Positive, AfterValidator(_cap_duration)]


class Controller(BaseModel):
    """PID gains and the force limit; omitted ones take the model's loop defaults."""

    model_config = _STRICT

    Kp: NonNegative | None = Field(None, description="proportional gain [N/m], >= 0")
    Ki: NonNegative | None = Field(None, description="integral gain [N/(m·s)], >= 0")
    Kd: NonNegative | None = Field(None, description="derivative gain on ṙ − ẋ [N·s/m], >= 0")
    u_max: Positive | None = Field(None, description="force limit |u| <= u_max [N]; null: "
                                   "none. Only the output is clamped: the integrator winds up")


class Reference(BaseModel):
    """r(t): a step of height h, a ramp at speed w from rest, a sine of amplitude h
    and frequency f. The fields the kind does not use are ignored."""

    model_config = _STRICT

    kind: Literal["step", "ramp", "sine"] | None = Field(None, description="default: step")
    h: NonZero | None = Field(None, description="step height, sine amplitude [m], != 0")
    w: NonZero | None = Field(None, description="ramp speed [m/s], != 0")
    f: Positive | None = Field(None, description="sine frequency [Hz], > 0 (at most "
                               f"{MAX_SINE_PERIODS} periods in the run)")


class SteadyParams(BaseModel):
    """F_m's (E2) parameters; each omitted one is the plant's."""

    model_config = _STRICT

    Fc: Positive | None = Field(None, description="Coulomb level [N]")
    Fs: Positive | None = Field(None, description="Stribeck level [N], >= Fc")
    V: Positive | None = Field(None, description="Stribeck velocity [m/s]")
    delta: Delta | None = Field(None, description="shape exponent, |δ| ≥ 0.05")
    sigma: NonNegative | None = Field(None, description="viscous coefficient [N·s/m]")


class Compensation(BaseModel):
    """c·F_m(ṙ) added to u: F_m = Fss(ṙ) of (E2)."""

    model_config = _STRICT

    scale: NonNegative = Field(0.0, description="c: 0 off, 1 exact, other values under- "
                               "and over-compensation")
    params: SteadyParams | None = Field(None, description="F_m's parameters (e.g. an "
                                        "identified model); omitted: the plant's")


class LoopRequest(PlantRequest):
    """The position loop: the plant (fields as ``/api/simulate``; LuGre takes ``z_ba`` too,
    the fraction of its steady deflection its bristle reaches at break-away), the
    controller, the reference, the run's length and the compensation."""

    lugre_lacks: ClassVar[tuple[str, ...]] = ("s",)

    F_hat: FHat | None = Field(None, description="F̂ of the phases' E13 values (default avg)")
    controller: Controller = Field(default_factory=Controller)
    reference: Reference = Field(default_factory=Reference)
    duration: Duration | None = Field(None, description="simulated time [s] (default 5, "
                                      "capped by BREAKAWAY_LOOP_MAX_DURATION)")
    points: GridSize | None = Field(None, description="samples of the uniform output grid "
                                    "(default 2000, capped); events are added")
    compensation: Compensation = Field(default_factory=Compensation)

    @model_validator(mode="after")
    def _across_fields(self) -> LoopRequest:
        reference = self.resolved_reference()
        if reference["kind"] == "sine" and reference["f"] * self.run_length() > MAX_SINE_PERIODS:
            raise _field_error("f", reference["f"], f"a run holds at most {MAX_SINE_PERIODS} "
                               "sine periods: lower f or the duration", ("reference", "f"))
        params = self.compensation_params()
        if params["Fs"] < params["Fc"]:
            raise _field_error("Fs", params["Fs"], f"Fs must be >= Fc, got Fs={params['Fs']} "
                               f"< Fc={params['Fc']}", ("compensation", "params", "Fs"))
        return self

    def defaults(self) -> dict:
        return LOOP_DEFAULTS[self.model]

    def run_length(self) -> float:
        return float(self.duration or LOOP_COMMON["duration"])

    def plant_params(self) -> dict[str, float]:
        """The plant's full parameters (``simulate_loop``'s ``params``)."""
        if self.model == "lugre":
            params = self.lugre_params()
            params["m"] = float(self.m or self.defaults()["m"])
        else:
            params = self.presliding_params()
            params["m"] = float(self.m or self.defaults()["m"])
        params["z_ba"] = float(self.z_ba or LOOP_COMMON["z_ba"])
        return params

    def resolved_controller(self) -> dict:
        given = self.controller.model_dump()
        return {name: given[name] if given[name] is not None else self.defaults()[name]
                for name in ("Kp", "Ki", "Kd", "u_max")}

    def resolved_reference(self) -> dict:
        given = self.reference.model_dump()
        out = {name: float(given[name] if given[name] is not None else self.defaults()[name])
               for name in ("h", "w", "f")}
        return {"kind": given["kind"] or LOOP_COMMON["kind"], **out}

    def compensation_params(self) -> dict[str, float]:
        """F_m's parameters: the request's, the rest the plant's steady state."""
        plant = self.plant_params()
        if self.model == "lugre":
            steady = {"Fc": plant["Fc"], "Fs": plant["Fs"], "V": plant["vs"],
                      "delta": plant["delta"], "sigma": plant["sigma2"]}
        else:
            steady = {name: plant[name] for name in ("Fc", "Fs", "V", "delta", "sigma")}
        given = (self.compensation.params.model_dump(exclude_none=True)
                 if self.compensation.params else {})
        return {**steady, **given}

    def worker_args(self) -> dict:
        """Keyword arguments of ``breakaway.loop.loop_experiment``."""
        return {"model": self.model, "params": self.plant_params(),
                "controller": self.resolved_controller(), "reference": self.resolved_reference(),
                "duration": self.run_length(),
                "compensation": {"scale": float(self.compensation.scale),
                                 "params": self.compensation_params()},
                "F_hat": self.F_hat or LOOP_COMMON["F_hat"],
                "points": int(self.points or LOOP_COMMON["points"]),
                "max_steps": self.step_budget()}


# ---------------------------------------------------------------------------------
# response
# ---------------------------------------------------------------------------------


class StickPhase(BaseModel):
    t_start: float | None = Field(description="start: t = 0 or the first reversal of ẋ "
                                  "after a break-away [s]")
    t_ba: float | None = Field(description="break-away: the presliding fraction reaches z* [s]")
    k: float | None = Field(description="mean rate of u over the phase towards the "
                            "break-away [N/s]")
    u_ba: float | None = Field(description="u at break-away [N] (signed)")
    E13: float | None = Field(description="(E13) at k, signed like u_ba [N]; null where k <= 0")
    u_start: float | None = Field(description="u at the phase's start [N]")
    F_ba: float | None = Field(description="friction at break-away [N]")
    direction: int = Field(description="sign of ẋ at break-away")


class Hunting(BaseModel):
    period: float = Field(description="mean spacing of the break-aways in the last half [s]")
    amplitude: float | None = Field(description="half the peak-to-peak of e there [m]")
    count: int = Field(description="break-aways in the last half")
    cycle: float | None = Field(description="mean spacing of break-aways in the same "
                                "direction [s] (a full cycle when they alternate)")


class LoopResponse(BaseModel):
    """One loop run: samples on the uniform grid plus each break-away and stick start
    (float32 precision), the stick phases beside E13, hunting and the RMS error."""

    model: Literal["presliding", "lugre"]
    t: Floats = Field(description="time [s]")
    r: Floats = Field(description="reference [m]")
    x: Floats = Field(description="position [m]")
    v: Floats = Field(description="velocity ẋ [m/s]")
    u: Floats = Field(description="control force [N]")
    F: Floats = Field(description="friction [N]")
    e: Floats = Field(description="error r − x [m]")
    stick_phases: list[StickPhase]
    hunting: Hunting | None = Field(description="null: the loop settles (fewer than two "
                                    "break-aways in the last half)")
    rms_error: float | None = Field(description="RMS of e over the run [m]")
    t_end: float = Field(description="where the run ended [s]: the duration, or earlier "
                         "when the loop ran away or the step budget ran out")
    runaway: bool = Field(description="the loop ran away (|e| beyond 100× the reference's "
                          "scale): unstable")
    reversals: int = Field(description="changes of sign of ẋ")
    params: dict[str, float] = Field(description="the plant's parameters the run used")
    controller: dict[str, float | None] = Field(description="Kp, Ki, Kd, u_max used")
    reference: dict[str, float | str] = Field(description="kind, h, w, f used")
    compensation: dict[str, float | dict[str, float]] = Field(
        description="scale and F_m's parameters used")
    duration: float
    F_hat: FHat


__all__ = ["LoopRequest", "LoopResponse"]
