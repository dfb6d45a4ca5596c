"""What one plan is made for: the rig's limits, the noise of a measurement, the
parameters held as given, the readings of (E13), and the units of the record."""

from __future__ import annotations

from dataclasses import dataclass, field

#: Default number of runs per family (the sine is one record).
DEFAULT_RUNS = {"ramps": 12, "steady": 12, "sine": 1}
#: Default number of candidate design points (rates, speeds; the sine's amplitudes
#: times its frequencies).
DEFAULT_GRID = {"ramps": 96, "steady": 96, "sine": 100}


@dataclass(frozen=True)
class Limits:
    """The rig's limits, in the record's units.

    Attributes
    ----------
    u_max : float
        The largest force the rig applies [N].
    v_max : float
        The largest speed it may reach or measure [m/s].
    v_min : float
        The slowest speed it holds steadily [m/s] (set-points).
    travel : float or None
        Its travel [m] (peak to peak; None: unlimited, a rotary axis).
    duration : float
        The longest one run may last [s] (a ramp, or the sine record).
    sample_rate : float
        Samples per second of a recorded run [Hz] (the sine).
    """

    u_max: float
    v_max: float
    v_min: float
    travel: float | None
    duration: float
    sample_rate: float

    def as_dict(self) -> dict:
        return {"u_max": self.u_max, "v_max": self.v_max, "v_min": self.v_min,
                "travel": self.travel, "duration": self.duration,
                "sample_rate": self.sample_rate}


@dataclass(frozen=True)
class Setting:
    """Everything a family needs besides the parameters.

    Attributes
    ----------
    limits : Limits
    noise : float
        Standard deviation of one measured force [N] (a break-away force, a set-point's
        force, one sample of a record).
    F_hat, z_ba :
        The reading of (E12)/(E13) that ramps are predicted with.
    units : dict
        Units of ``F``, ``x``, ``v``, ``t``, ``k`` (linear or rotary).
    grid : int
        Candidate design points.
    """

    limits: Limits
    noise: float
    F_hat: str = "avg"
    z_ba: float = 0.95
    units: dict = field(default_factory=lambda: {"F": "N", "x": "m", "v": "m/s", "t": "s",
                                                  "k": "N/s"})
    grid: int = 96


__all__ = ["DEFAULT_GRID", "DEFAULT_RUNS", "Limits", "Setting"]
