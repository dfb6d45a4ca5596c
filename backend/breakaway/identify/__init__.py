"""Identification: fit measured data, trace the residual to the effect the model lacks,
add it, and report the error before and after.

>>> from breakaway.identify import read_csv, identify
>>> report = identify(read_csv("run.csv"))          # doctest: +SKIP
"""

from __future__ import annotations

from .csvdata import DataError, Dataset, parse_csv, read_csv
from .diagnosis import Diagnosis, diagnose
from .effects import EFFECTS, effects_for
from .fitting import FitError, FitResult, fit_model
from .report import report


def identify(data: Dataset, progress=None) -> dict:
    """The identification report of ``data`` (see :func:`breakaway.identify.diagnosis.diagnose`)."""
    return report(diagnose(data, progress))


__all__ = ["DataError", "Dataset", "Diagnosis", "EFFECTS", "FitError", "FitResult",
           "diagnose", "effects_for", "fit_model", "identify", "parse_csv", "read_csv",
           "report"]
