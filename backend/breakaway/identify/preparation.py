"""The rows a fit uses: rows the model cannot use dropped (``dropped-rows``), spikes set
aside (``outliers``, found by :mod:`.outliers`), and row subsets of a dataset."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .csvdata import MIN_ROWS, Dataset
from .fitting import FitError
from .models import with_forces
from .outliers import SPIKE_SIGMAS, despiked_force
from .warnings import warning


def subset(data: Dataset, rows, segments=()) -> Dataset:
    """The same dataset restricted to ``rows`` (indices, in order)."""
    rows = np.asarray(rows)
    return Dataset(kind=data.kind, columns={k: v[rows] for k, v in data.columns.items()},
                   meta=data.meta, n=int(rows.size), ignored_columns=data.ignored_columns,
                   lines=data.lines[rows], meta_lines=data.meta_lines,
                   segments=tuple(segments), printed=data.printed,
                   weights=None if data.weights is None else data.weights[rows])


def prepare(data: Dataset) -> tuple[Dataset, list[dict]]:
    """Drop the rows the model cannot use: steady rows at v = 0 (E2 has no force there,
    the measured one is whatever stiction held)."""
    if data.kind != "steady":
        return data, []
    at_rest = data.columns["v"] == 0
    count = int(np.count_nonzero(at_rest))
    if not count:
        return data, []
    kept = np.flatnonzero(~at_rest)
    if kept.size < MIN_ROWS:
        raise FitError(f"only {kept.size} rows have v ≠ 0; at least {MIN_ROWS} are needed")
    lines = ", ".join(str(int(x)) for x in data.lines[at_rest][:5])
    more = ", …" if count > 5 else ""
    return subset(data, kept), [warning(
        "dropped-rows", None,
        f"{count} of {data.n} rows have v = 0 (lines {lines}{more}); steady friction is not "
        "defined at rest, so they were left out")]


def without_spikes(data: Dataset, spikes) -> Dataset:
    """``data`` with its spikes set aside: a time series keeps every row (its presliding
    state runs along x) with each spike's F replaced by the median of its neighbours';
    the other kinds' rows are separate measurements, and a spike's row is left out."""
    if data.kind != "timeseries":
        return subset(data, np.flatnonzero(~spikes))
    return with_forces(data, despiked_force(data.columns["F"], spikes))


@dataclass
class SetAside:
    """The spikes set aside so far (:mod:`.outliers`), for the report's warning."""

    rows: int  # rows of the data before any was set aside
    base_rmse: float  # the base model's RMSE with the spikes in [N]
    lines: list = field(default_factory=list)
    spreads: list = field(default_factory=list)

    def add(self, data: Dataset, spikes, scale) -> None:
        self.lines.extend(int(line) for line in data.lines[spikes])
        self.spreads.extend(float(value) for value in scale[spikes])

    def warning(self, kind: str, unit: str = "N") -> dict:
        count = len(self.lines)
        lines = ", ".join(str(line) for line in sorted(self.lines)[:5])
        more = ", …" if count > 5 else ""
        done = ("their F was replaced by the median of their neighbours'"
                if kind == "timeseries" else "they were left out")
        return warning("outliers", "F_ba" if kind == "breakaway" else "F", (
            f"{count} of {self.rows} rows (lines {lines}{more}) are isolated spikes, more "
            f"than {SPIKE_SIGMAS:g} times the residual's local spread "
            f"({float(np.median(self.spreads)):.3g} {unit}) from their neighbours: glitches of "
            f"the measurement, not friction; {done}, and the base model's RMSE with them "
            f"was {self.base_rmse:.4g} {unit}"))


__all__ = ["SetAside", "prepare", "subset", "without_spikes"]
