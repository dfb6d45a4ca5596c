"""What one search records: the steps it took and its last verdict on each effect."""

from __future__ import annotations

from dataclasses import dataclass

from .fitting import FitResult


@dataclass
class Step:
    """One effect accepted: the fit with it, the evidence, its held-out error [N]."""

    effect: str
    fit: FitResult
    evidence: str
    heldout: float


@dataclass
class Candidate:
    """The last verdict on one library effect."""

    rmse: float | None = None
    bic: float | None = None
    heldout: float | None = None
    accepted: bool = False
    reason: str | None = None


__all__ = ["Candidate", "Step"]
