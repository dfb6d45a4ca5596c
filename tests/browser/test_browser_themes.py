"""Presentation mode, dark mode and print: how the explorer looks in a lecture hall."""

from __future__ import annotations

import pytest

pytestmark = pytest.mark.browser

PLOTS = ("stribeck", "hysteresis", "phase", "breakaway", "ramp")


def layout(explorer, plot: str, path: str):
    return explorer.page.evaluate(
        f"(id) => document.getElementById('plot-' + id).layout.{path}", plot)


def test_presentation_mode_from_the_url_and_the_toggle(explorer):
    explorer.open("?sim=0&present=1")
    for plot in PLOTS:
        assert layout(explorer, plot, "xaxis.tickfont.size") >= 18, plot
        assert layout(explorer, plot, "yaxis.tickfont.size") >= 18, plot
    ticks = explorer.page.evaluate(
        "getComputedStyle(document.querySelector('#plot-stribeck .xtick text')).fontSize")
    assert float(ticks.rstrip("px")) >= 18
    width = explorer.page.evaluate(
        "document.getElementById('plot-stribeck').data[0].line.width")
    assert width >= 3
    toggle = explorer.page.get_by_label("Presentation mode (large type, heavy lines)")
    assert toggle.is_checked()
    toggle.uncheck()
    explorer.ready()
    assert (layout(explorer, "stribeck", "xaxis.tickfont") or {}).get("size", 11) < 18
    assert "present=1" not in explorer.page.url


def test_dark_mode_follows_the_system(explorer):
    explorer.page.emulate_media(color_scheme="dark")
    explorer.open("?sim=0")
    background = explorer.page.evaluate("getComputedStyle(document.documentElement).backgroundColor")
    red, green, blue = (int(v) for v in background[background.index("(") + 1:-1].split(",")[:3])
    assert max(red, green, blue) < 60
    assert layout(explorer, "stribeck", "paper_bgcolor") == "rgba(0,0,0,0)"
    assert layout(explorer, "stribeck", "font.color") == "#e4e7eb"


def test_print_shows_the_plots_without_the_controls(explorer):
    explorer.open("?sim=0")
    explorer.page.emulate_media(media="print")
    assert not explorer.page.locator("#controls").is_visible()
    assert explorer.page.locator("#plot-breakaway").is_visible()
    assert explorer.page.locator("#ba-explain").is_visible()
