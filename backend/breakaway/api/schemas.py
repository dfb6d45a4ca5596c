"""Pydantic request and response models of the HTTP API.

Every constraint of the model's parameters is carried here, so a bad value is a 422 that names the
field before any model code runs. Requests are strict: numbers must be JSON numbers
(no strings, no booleans), finite (no NaN/Infinity), and unknown fields are rejected.
"""

from __future__ import annotations

from typing import Annotated, ClassVar, Literal

from pydantic import (
    AfterValidator,
    BaseModel,
    ConfigDict,
    Field,
    ValidationInfo,
    field_validator,
    model_validator,
)

from ..params import DEFAULTS, LUGRE_1995, MAGNITUDE
from ..settings import get_settings

#: δ ≠ 0, and |δ| ≥ 0.05 in practice.
MIN_ABS_DELTA = 0.05

_STRICT = ConfigDict(strict=True, allow_inf_nan=False, extra="forbid")

FHat = Literal["Fc", "Fs", "avg", "self"]


def _check_delta(value: float | None) -> float | None:
    if value is not None and abs(value) < MIN_ABS_DELTA:
        raise ValueError(f"delta must satisfy |delta| >= {MIN_ABS_DELTA} (delta != 0)")
    return value


def _cap_grid(value: int) -> int:
    cap = get_settings().max_grid_points
    if value > cap:
        raise ValueError(f"grid size must be <= {cap}, got {value}")
    return value


def _cap_rates(value: list[float]) -> list[float]:
    cap = get_settings().max_rates
    if len(value) > cap:
        raise ValueError(f"at most {cap} rates per request, got {len(value)}")
    return value




def _check_magnitude(value: float | None) -> float | None:
    low, high = MAGNITUDE
    if value is not None and value != 0 and not low <= abs(value) <= high:
        raise ValueError(f"must lie between {low:g} and {high:g} in magnitude "
                         f"(0 where 0 is allowed), got {value:g}")
    return value


def _check_at_most(value: float | None) -> float | None:
    high = MAGNITUDE[1]
    if value is not None and abs(value) > high:
        raise ValueError(f"must be at most {high:g}, got {value:g}")
    return value


_LOW, _HIGH = MAGNITUDE
Magnitude = AfterValidator(_check_magnitude)
# the bounds go into the OpenAPI schema too (minimum/maximum), so a client that follows
# the schema is never refused for them; a tiny non-negative coefficient (σ = 1e-310) is
# harmless and taken as it is
Positive = Annotated[float, Field(gt=0, json_schema_extra={"minimum": _LOW, "maximum": _HIGH}),
                     Magnitude]
NonNegative = Annotated[float, Field(ge=0, json_schema_extra={"maximum": _HIGH}),
                        AfterValidator(_check_at_most)]
Delta = Annotated[float, AfterValidator(_check_delta), Magnitude, Field(json_schema_extra={
    "anyOf": [{"minimum": MIN_ABS_DELTA, "maximum": _HIGH},
              {"minimum": -_HIGH, "maximum": -MIN_ABS_DELTA}]})]
GridSize = Annotated[int, Field(ge=10), AfterValidator(_cap_grid)]
Rate = Positive
Rates = Annotated[list[Rate], Field(min_length=1), AfterValidator(_cap_rates)]


class _Levels(BaseModel):
    """Fc and Fs with the cross-constraint Fs ≥ Fc reported on ``Fs``."""

    model_config = _STRICT

    Fc: Positive = Field(DEFAULTS["Fc"], description="Coulomb level [N], > 0")
    Fs: Positive = Field(DEFAULTS["Fs"], validate_default=True,
                      description="Stribeck (stiction) level [N], >= Fc")

    @field_validator("Fs")
    @classmethod
    def _fs_at_least_fc(cls, value: float, info: ValidationInfo) -> float:
        Fc = info.data.get("Fc")
        if Fc is not None and value < Fc:
            raise ValueError(f"Fs must be >= Fc, got Fs={value} < Fc={Fc}")
        return value


# ---------------------------------------------------------------------------------
# requests
# ---------------------------------------------------------------------------------


class ExploreGrid(BaseModel):
    """Optional grid sizes of one frame (defaults: ``breakaway.frame.FRAME_GRID``)."""

    model_config = _STRICT

    stribeck: GridSize | None = Field(None, description="points of Fss(v)")
    loop: GridSize | None = Field(None, description="samples of the hysteresis loop")
    phase: GridSize | None = Field(None, description="points per phase curve")
    breakaway: GridSize | None = Field(None, description="rates of the F_ba(k) curves")

    def sizes(self) -> dict[str, int]:
        return {key: value for key, value in self.model_dump().items() if value is not None}


class ExploreRequest(_Levels):
    """One explorer redraw; every field is optional (defaults: ``breakaway.params.DEFAULTS``)."""

    V: Positive = Field(DEFAULTS["V"], description="Stribeck velocity [m/s], > 0")
    delta: Delta = Field(DEFAULTS["delta"], description="Stribeck shape exponent, |δ| ≥ 0.05")
    sigma: NonNegative = Field(DEFAULTS["sigma"], description="viscous coefficient [N·s/m], ≥ 0")
    s: Positive = Field(DEFAULTS["s"], description="presliding scale [1/m], > 0")
    z_ba: Positive = Field(DEFAULTS["z_ba"], lt=1, description="break-away fraction z*, in (0, 1)")
    m: Positive = Field(DEFAULTS["m"],
                     description="moving mass [kg], > 0 (accepted for symmetry with "
                                 "/api/simulate; the quasi-static frame does not use it)")
    k: Positive = Field(DEFAULTS["k"], description="current force rate [N/s], > 0")
    F_hat: FHat = Field(DEFAULTS["F_hat"], description="level F̂ of (E12)")
    grid: ExploreGrid | None = Field(None, description="grid sizes (capped)")

    def params(self) -> dict[str, float | str]:
        """The model parameters (keys of ``DEFAULTS``)."""
        return self.model_dump(exclude={"grid"})


class PlantRequest(_Levels):
    """The friction model and its parameters, as the simulation requests share them.

    Omitted parameters take the model's defaults: ``breakaway.params.DEFAULTS`` for
    ``presliding``, ``breakaway.params.LUGRE_1995`` for ``lugre``. For ``lugre`` the
    request fields override LuGre's as ``Fc → Fc``, ``Fs → Fs``, ``V → vs``,
    ``delta → delta``, ``sigma → sigma2``, ``m → m``, ``sigma0``, ``sigma1``;
    the fields in ``lugre_lacks`` do not exist in LuGre and are rejected.
    """

    #: the presliding parameters LuGre has no use for in this request
    lugre_lacks: ClassVar[tuple[str, ...]] = ("s", "z_ba")

    model: Literal["presliding", "lugre"] = Field("presliding", description="which model")
    V: Positive | None = Field(None, description="Stribeck velocity [m/s] (LuGre: vs)")
    delta: Delta | None = Field(None, description="shape exponent, |δ| ≥ 0.05")
    sigma: NonNegative | None = Field(None, description="viscous coefficient [N·s/m] (LuGre: σ2)")
    s: Positive | None = Field(None, description="presliding scale [1/m] (presliding only)")
    z_ba: Positive | None = Field(None, lt=1, description="break-away fraction z* (presliding only)")
    m: Positive | None = Field(None, description="moving mass [kg]")
    sigma0: Positive | None = Field(None, description="LuGre bristle stiffness [N/m] (lugre only)")
    sigma1: NonNegative | None = Field(None, description="LuGre bristle damping [N·s/m] (lugre only)")
    max_steps: int | None = Field(
        None, ge=1000, description="integrator steps per rate, at most the server's "
        "BREAKAWAY_SIMULATE_MAX_STEPS (the default); a rate that needs more reports null "
        "(how an interactive page bounds its wait)")

    def step_budget(self) -> int:
        """The steps per rate this request may use."""
        cap = get_settings().simulate_max_steps
        return cap if self.max_steps is None else min(self.max_steps, cap)

    @model_validator(mode="after")
    def _fields_of_the_model(self) -> PlantRequest:
        unused = ("sigma0", "sigma1") if self.model == "presliding" else self.lugre_lacks
        for name in unused:
            if getattr(self, name) is not None:
                raise _field_error(name, getattr(self, name),
                                   f"{name} is not a parameter of model {self.model!r}")
        return self

    def presliding_params(self) -> dict[str, float]:
        """Keyword arguments of ``breakaway.dynamics.simulate_breakaway``."""
        names = ("Fc", "Fs", "V", "delta", "sigma", "s", "m", "z_ba")
        return {name: float(DEFAULTS[name] if getattr(self, name) is None else getattr(self, name))
                for name in names}

    def lugre_params(self) -> dict[str, float]:
        """``LUGRE_1995`` with this request's overrides (``params`` of the LuGre simulation)."""
        mapping = {"Fc": "Fc", "Fs": "Fs", "V": "vs", "delta": "delta", "sigma": "sigma2",
                   "m": "m", "sigma0": "sigma0", "sigma1": "sigma1"}
        params = dict(LUGRE_1995)
        for field, key in mapping.items():
            value = getattr(self, field)
            if value is not None:
                params[key] = float(value)
        return params


class SimulateRequest(PlantRequest):
    """Ramp simulation (E7) or LuGre at each rate in ``k`` (fields of the model: see
    :class:`PlantRequest`)."""

    k: Rates = Field(..., description="force rates [N/s], each > 0 (capped in number)")


class RampRequest(SimulateRequest):
    """The ramp experiment at one rate (``POST /api/ramp``); fields as
    ``/api/simulate`` with a single ``k``, and ``F_hat`` for the E13 value beside it."""

    k: Positive = Field(..., description="force rate [N/s], > 0")
    F_hat: Literal["Fc", "Fs", "avg", "self"] | None = Field(
        None, description="F̂ of the E13 value (default of breakaway.params.DEFAULTS)")

    def worker_params(self) -> dict[str, float | str]:
        params = self.lugre_params() if self.model == "lugre" else self.presliding_params()
        return {**params, "F_hat": self.F_hat or DEFAULTS["F_hat"]}


def _field_error(name: str, value: object, message: str, loc: tuple | None = None):
    """A pydantic ValidationError located at ``name`` (for checks across fields), or at
    ``loc`` inside a nested object."""
    from pydantic_core import ValidationError

    return ValidationError.from_exception_data(
        "SimulateRequest",
        [{"type": "value_error", "loc": loc or (name,), "input": value,
          "ctx": {"error": message}}],
    )


# ---------------------------------------------------------------------------------
# responses
# ---------------------------------------------------------------------------------

Floats = list[float | None]


class StribeckCurve(BaseModel):
    v: Floats = Field(description="velocity [m/s]")
    F: Floats = Field(description="Fss(v) [N] (E2)")


class HysteresisLoop(BaseModel):
    x: Floats = Field(description="displacement [m]")
    F: Floats = Field(description="friction [N] (E6')")


class PhaseCurve(BaseModel):
    k: float = Field(description="force rate [N/s]")
    v: Floats = Field(description="ẋ(z) [m/s] (E12)")


class PhaseFamily(BaseModel):
    z: Floats = Field(description="normalised presliding distance [-]")
    curves: list[PhaseCurve] = Field(description="the note's Fig. 3 rates, then the current k")


class BreakawayCurves(BaseModel):
    model_config = ConfigDict(populate_by_name=True)

    k: Floats = Field(description="force rate grid [N/s]")
    Fc: Floats = Field(description="F_ba(k) with F̂ = Fc [N] (E13)")
    Fs: Floats = Field(description="F_ba(k) with F̂ = Fs [N]")
    avg: Floats = Field(description="F_ba(k) with F̂ = (Fc + Fs)/2 [N]")
    self_: Floats = Field(alias="self", description="F_ba(k) with the self-consistent F̂ [N]")


class ExploreResponse(BaseModel):
    """The payload of one redraw. Floats carry ``settings.payload_digits`` significant
    digits; a non-finite value is ``null``."""

    stribeck: StribeckCurve
    hysteresis: HysteresisLoop
    phase: PhaseFamily
    breakaway: BreakawayCurves


class SimulateResponse(BaseModel):
    """Break-away of the simulated ramp at each rate; ``null`` where none happened
    within the step budget."""

    model: Literal["presliding", "lugre"]
    k: list[float] = Field(description="force rates [N/s]")
    u_ba: Floats = Field(description="actuation force k·t_ba at break-away [N]")
    F_ba: Floats = Field(description="friction at break-away [N] (LuGre: first local max)")
    t_ba: Floats = Field(description="break-away time [s]")
    reversals: list[int] = Field(description="motion reversals before break-away")
    params: dict[str, float] = Field(description="the parameters the simulation used")


class RampResponse(BaseModel):
    """One ramp run up to break-away (thinned to at most 2000 samples) and E13."""

    model: Literal["presliding", "lugre"]
    k: float = Field(description="force rate [N/s]")
    t: Floats = Field(description="time [s]")
    x: Floats = Field(description="position [m]")
    v: Floats = Field(description="velocity ẋ [m/s]")
    u: Floats = Field(description="actuation u = k·t [N]")
    F: Floats = Field(description="friction [N]")
    z: Floats = Field(description="s·|x − x_r| (presliding) or LuGre's bristle state z [m]")
    t_ba: float | None = Field(description="break-away time [s]; null if none in the budget")
    u_ba: float | None = Field(description="actuation at break-away k·t_ba [N]")
    F_ba: float | None = Field(description="friction at break-away [N]")
    E13: float = Field(description="quasi-static break-away force of (E13) at this k [N]")
    reversals: int = Field(description="motion reversals before break-away")
    params: dict[str, float | str] = Field(description="the parameters the run used")


class Preset(BaseModel):
    name: str
    description: str
    units: Literal["normalised", "SI"] = Field(
        description="normalised: the note's s = 1 scaling (velocities in presliding "
                    "distances per second); SI: metres, newtons, seconds")
    params: dict[str, float | str]


class Control(BaseModel):
    name: str
    symbol: str
    unit: str
    help: str
    group: Literal["stribeck", "presliding", "dynamics"]
    scale: Literal["log", "log0", "linear"]
    min: float
    max: float
    step: float | None = None


class PresetsResponse(BaseModel):
    presets: list[Preset]
    parameters: list[Control] = Field(description="the explorer's controls: one table of "
                                      "symbols, units, slider ranges and help texts")
    defaults: dict[str, float | str] = Field(description="breakaway.params.DEFAULTS")
    lugre_1995: dict[str, float] = Field(description="LuGre (1995) parameters of /api/simulate")


class Health(BaseModel):
    status: str
    version: str
    worker: int = Field(description="process id of the server process that answered")
