"""GET /api/samples: bundled datasets parse, and each mystery holds what it says."""

from __future__ import annotations

import pytest

from breakaway.identify import identify, parse_csv
from breakaway.identify.samples import SAMPLES


def test_list(client):
    response = client.get("/api/samples")
    assert response.status_code == 200
    listed = response.json()
    assert [s["name"] for s in listed] == list(SAMPLES)
    assert {s["kind"] for s in listed} == {"timeseries", "steady", "breakaway"}


def test_unknown_sample_is_404(client):
    assert client.get("/api/samples/nope.csv").status_code == 404


def test_measured_sample_keeps_its_attribution(client):
    text = client.get("/api/samples/damper.csv").text
    assert "CC BY-SA 4.0" in text and "ARTS-Lab" in text
    assert parse_csv(text).n == 4096


@pytest.mark.parametrize("name,effects,unexplained", [
    ("mystery-a", ["backlash"], False),
    ("mystery-b", ["ripple"], False),
    ("mystery-c", ["asymmetry"], False),
    ("mystery-d", ["dwell"], False),
    ("mystery-e", [], False),
    ("mystery-f", [], True),
])
def test_samples_hold_what_they_promise(client, name, effects, unexplained):
    response = client.get(f"/api/samples/{name}.csv")
    assert response.status_code == 200
    data = parse_csv(response.text)
    assert data.kind == SAMPLES[name].kind
    # nothing in the file declares the effect
    assert not any(e in response.text.split("\n", 1)[0] for e in ("backlash", "ripple"))
    report = identify(data)
    assert report["effects"] == effects
    assert report["unexplained"] is unexplained


EFFECT_WORDS = ("viscous", "asymmetr", "offset", "drift", "inertia", "ripple", "wobbl", "lag",
                "backlash", "play", "dwell", "reversal", "detection", "nothing missing",
                "library", "base model")


def test_quiz_descriptions_name_no_effect(client):
    for sample in client.get("/api/samples").json():
        if not sample["quiz"]:
            continue
        text = (sample["title"] + " " + sample["description"]).lower()
        assert not [w for w in EFFECT_WORDS if w in text], sample["name"]
        text = client.get(f"/api/samples/{sample['name']}.csv").text
        comments = " ".join(line for line in text.splitlines()[:5] if line.startswith("#"))
        assert not [w for w in EFFECT_WORDS if w in comments.lower()], sample["name"]
