"""The effect library: each effect is one object, in one module.

An :class:`Effect` knows everything about itself that the fit, the diagnosis, the
report, the text and the data panel need: its name and kinds, its parameters (units,
bounds, transform), when the data can show it (:meth:`Effect.unavailable`), starting
values read off a residual (:meth:`Effect.starts`), the residual signature that points to
it (:meth:`Effect.signature`), the regressor its residual plot uses, and how it changes
the prediction (the hooks below, called by :mod:`breakaway.identify.models` in a fixed
order). Adding an effect means adding one module here and one line to :data:`EFFECTS`.

Prediction hooks (each returns its input unchanged unless the effect overrides it):

``body_motion(pb, p, ctx)``   timeseries: the sliding body's x, v, d, engaged (play)
``slip_velocity(pb, p, v)``   the velocity g is evaluated at (frictional lag)
``levels(pb, p, Fc, Fs, neg)`` per-row (Fc, Fs): negative-direction levels, dwell
``scale_g(pb, p, g)``         the Stribeck magnitude (drift)
``target(pb, p, v)``          added to the steady target d·g (viscous σ·v)
``sensor(pb, p, F, ctx)``     what the sensor adds to the friction (offset, inertia, …)
"""

from __future__ import annotations

from ..csvdata.dataset import unit_of
from .asymmetry import Asymmetry
from .backlash import Backlash, engaged_presliding, play_operator
from .base import (
    BASE_PARAMS,
    BREAKAWAY_Z,
    DELTA_BOUNDS,
    MIN_RATES,
    MIN_RIPPLE_PERIODS,
    Effect,
    Param,
)
from .detection import Detection, viscous_equivalent_of_detection
from .drift import Drift
from .dwell import Dwell
from .inertia import Inertia
from .lag import Lag, lag_filter
from .offset import Offset
from .ripple import Ripple, long_wavelength, periodogram
from .viscous import Viscous
from .viscous_power import ViscousPower

#: The library, in the order the prediction hooks run.
EFFECTS: dict[str, Effect] = {e.name: e for e in (
    Viscous(), ViscousPower(), Asymmetry(), Offset(), Drift(), Inertia(), Ripple(), Lag(), Backlash(),
    Dwell(), Detection())}


def effects_for(kind: str) -> list[Effect]:
    """The library's effects that apply to ``kind``, in library order."""
    return [e for e in EFFECTS.values() if kind in e.kinds]


def availability(problem) -> dict[str, str | None]:
    """Each effect of the problem's kind: None when the data can show it, else why not."""
    return {e.name: e.unavailable(problem) for e in effects_for(problem.kind)}


def param_spec(name: str, effects=()) -> Param:
    """The :class:`Param` of a base or effect parameter.

    Two effects may share a key (``viscous`` and ``viscous-power`` both have ``sigma``,
    and are never in one model): the ones in ``effects`` (names) are looked at first.
    """
    if name in BASE_PARAMS:
        return BASE_PARAMS[name]
    for effect in [*(EFFECTS[e] for e in effects), *EFFECTS.values()]:
        for p in effect.params:
            if p.name == name:
                return p
    raise KeyError(name)


__all__ = ["BASE_PARAMS", "BREAKAWAY_Z", "DELTA_BOUNDS", "EFFECTS", "Effect", "MIN_RATES",
           "MIN_RIPPLE_PERIODS", "Param", "availability", "effects_for", "engaged_presliding",
           "lag_filter", "long_wavelength", "param_spec", "periodogram", "play_operator",
           "unit_of", "viscous_equivalent_of_detection"]
