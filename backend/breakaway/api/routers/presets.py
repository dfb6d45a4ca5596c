"""GET /api/presets: the explorer's named parameter sets and the defaults."""

from __future__ import annotations

from fastapi import APIRouter

from ...params import CONTROLS, DEFAULTS, LUGRE_1995, NORMALISED_PRESETS, PRESET_DESCRIPTIONS, PRESETS
from ..schemas import Preset, PresetsResponse

router = APIRouter(prefix="/api", tags=["presets"])


@router.get("/presets", response_model=PresetsResponse)
def presets() -> PresetsResponse:
    return PresetsResponse(
        presets=[Preset(name=name, description=PRESET_DESCRIPTIONS.get(name, ""),
                        units="normalised" if name in NORMALISED_PRESETS else "SI",
                        params=params)
                 for name, params in PRESETS.items()],
        parameters=list(CONTROLS),
        defaults=DEFAULTS,
        lugre_1995=LUGRE_1995,
    )
