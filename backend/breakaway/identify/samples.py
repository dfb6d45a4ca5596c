"""Sample datasets for the explorer's data panel: the measured damper excerpt and
"mystery" synthetic sets, each with an effect the file does not declare."""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources

from .synthetic import make_dataset, make_filtered_channel, to_csv

#: Rows of the synthetic timeseries samples (a quick fit in the browser).
_SAMPLE_ROWS = 8000


@dataclass(frozen=True)
class Sample:
    name: str
    title: str
    kind: str
    description: str
    #: a puzzle for the data panel's quiz: the description names no effect
    quiz: bool = False

    def csv(self) -> str:
        return _MAKERS[self.name]()


def _mystery(kind, effects, seed):
    def make():
        data, _ = make_dataset(kind, effects, seed=seed,
                               n=_SAMPLE_ROWS if kind == "timeseries" else None)
        return to_csv(data, comment="synthetic sample (seeded)")
    return make


def _outside_library():
    data = make_filtered_channel(seed=31, n=_SAMPLE_ROWS)
    return to_csv(data, comment="synthetic sample (seeded)")


def _damper():
    return (resources.files("breakaway") / "samples" /
            "brfd_sine_1Hz_1in_36lb_excerpt.csv").read_text(encoding="utf-8")


SAMPLES: dict[str, Sample] = {s.name: s for s in (
    Sample("damper", "Measured: friction damper, 1 Hz", "timeseries",
           "4 s of a banded rotary friction damper under a 1 Hz sine (ARTS-Lab, CC BY-SA 4.0)."),
    Sample("mystery-a", "Mystery A (time series)", "timeseries",
           "An actuator moved back and forth in strokes of different lengths and speeds.",
           quiz=True),
    Sample("mystery-b", "Mystery B (time series)", "timeseries",
           "Another record of an actuator moved back and forth.", quiz=True),
    Sample("mystery-c", "Mystery C (Stribeck curve)", "steady",
           "Steady sliding at many speeds, both directions.", quiz=True),
    Sample("mystery-d", "Mystery D (break-away)", "breakaway",
           "Break-away forces at many rates, both directions, after different rest times.",
           quiz=True),
    Sample("mystery-e", "Mystery E (time series)", "timeseries",
           "A third actuator record: strokes back and forth.", quiz=True),
    Sample("mystery-f", "Mystery F (time series)", "timeseries",
           "A fourth actuator record: strokes back and forth.", quiz=True),
)}

_MAKERS = {
    "damper": _damper,
    "mystery-a": _mystery("timeseries", ("backlash",), 21),
    "mystery-b": _mystery("timeseries", ("ripple",), 22),
    "mystery-c": _mystery("steady", ("asymmetry",), 23),
    "mystery-d": _mystery("breakaway", ("dwell",), 24),
    "mystery-e": _mystery("timeseries", (), 25),
    "mystery-f": _outside_library,
}
