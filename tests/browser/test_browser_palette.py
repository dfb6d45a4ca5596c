"""Colours: every pair of distinct trace colours that share a plot lies at least 40 apart
(Euclidean, sRGB 0–255) for normal vision and under protan, deutan and tritan simulation
(Machado, Oliveira & Fernandes 2009, severity 1.0), light and dark; computed from the
palette module the figures use and from the traces the page draws."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from browser_model import until

pytestmark = pytest.mark.browser

#: Machado et al. (2009), Table 1 at severity 1.0, applied to linear RGB.
MACHADO = {
    "protan": np.array([[0.152286, 1.052583, -0.204868],
                        [0.114503, 0.786281, 0.099216],
                        [-0.003882, -0.048116, 1.051998]]),
    "deutan": np.array([[0.367322, 0.860646, -0.227968],
                        [0.280085, 0.672501, 0.047413],
                        [-0.011820, 0.042940, 0.968881]]),
    "tritan": np.array([[1.255528, -0.076749, -0.178779],
                        [-0.078411, 0.930809, 0.147602],
                        [0.004733, 0.691367, 0.303900]]),
}
MIN_DISTANCE = 40.0


def srgb(color: str) -> np.ndarray:
    text = color.strip().lstrip("#")
    if len(text) == 3:
        text = "".join(c * 2 for c in text)
    return np.array([int(text[i:i + 2], 16) for i in (0, 2, 4)], dtype=float)


def simulate(rgb: np.ndarray, kind: str) -> np.ndarray:
    """A colour as a person with the `kind` of colour blindness sees it [sRGB 0–255]."""
    c = rgb / 255.0
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    seen = np.clip(MACHADO[kind] @ linear, 0.0, 1.0)
    return 255.0 * np.where(seen <= 0.0031308, 12.92 * seen, 1.055 * seen ** (1 / 2.4) - 0.055)


def distances(a: str, b: str) -> dict[str, float]:
    x, y = srgb(a), srgb(b)
    out = {"normal": float(np.linalg.norm(x - y))}
    for kind in MACHADO:
        out[kind] = float(np.linalg.norm(simulate(x, kind) - simulate(y, kind)))
    return out


def too_close(colors) -> list[tuple[str, str, dict]]:
    out = []
    for a, b in itertools.combinations(sorted({c.lower() for c in colors}), 2):
        apart = distances(a, b)
        if min(apart.values()) < MIN_DISTANCE:
            out.append((a, b, {k: round(v, 1) for k, v in apart.items()}))
    return out


def test_the_simulation_reproduces_the_issues_figure():
    # issue 21: 'F̂ = Fs' (#d55e00) and the old 'line at the current k' (#e6550d) were 8
    # apart for deuteranopes, where other pairs were 40 or more
    assert distances("#d55e00", "#e6550d")["deutan"] == pytest.approx(7.6, abs=0.1)
    assert distances("#000000", "#ffffff")["normal"] == pytest.approx(441.7, abs=0.1)
    # white stays white, black black, for every kind
    for kind in MACHADO:
        np.testing.assert_allclose(simulate(srgb("#ffffff"), kind), 255.0, atol=0.6)
        np.testing.assert_allclose(simulate(srgb("#000000"), kind), 0.0, atol=1e-9)


def test_every_group_of_the_palette_keeps_its_colours_apart(explorer):
    explorer.open("?sim=0")
    groups, dark = explorer.page.evaluate("""async () => {
        const { PALETTE, DARK_INK } = await import('/js/plots/palette.js');
        return [PALETTE, DARK_INK]; }""")
    assert set(groups) >= {"stribeck", "hysteresis", "phase", "breakaway", "ramp",
                           "loopPosition", "loopError", "loopForce"}
    for name, group in groups.items():
        colors = [c for value in group.values() for c in (value if isinstance(value, list) else [value])]
        assert too_close(colors) == [], f"{name}, light"
        assert too_close([dark.get(c, c) for c in colors]) == [], f"{name}, dark"


def trace_colors(page) -> dict[str, list[str]]:
    """Per plot, the colours of its traces' lines and markers as drawn."""
    return page.evaluate("""() => {
        const out = {};
        for (const gd of document.querySelectorAll('#plots .js-plotly-plot')) {
          const colors = [];
          for (const trace of gd.data) {
            if (trace.line?.color) colors.push(trace.line.color);
            const marker = trace.marker?.color;
            if (marker) colors.push(...(Array.isArray(marker) ? marker : [marker]));
          }
          out[gd.id.replace('plot-', '')] = colors;
        }
        return out; }""")


@pytest.mark.parametrize("scheme", ["light", "dark"])
def test_the_plots_as_drawn_keep_their_colours_apart(explorer, scheme):
    # everything on at once: simulated points, LuGre, pinned curves and a sweep
    explorer.page.emulate_media(color_scheme=scheme)
    explorer.open("?sim=1&lugre=1&limit=1&u_max=1.2")  # the loop hunts: every mark drawn
    page = explorer.page
    page.get_by_role("button", name="Pin these curves").click()
    page.get_by_label("Sweep", exact=True).select_option("Fs")
    page.get_by_role("button", name="Run sweep").click()
    page.locator("#sweep-status").get_by_text("curves of").wait_for()
    explorer.sim_ready()
    page.evaluate("window.breakaway.rampReady()")
    until(page, "document.getElementById('plot-breakaway').data.some((t) => t.name.startsWith('LuGre'))")
    page.evaluate("window.breakaway.loopReady()")
    drawn = trace_colors(page)
    assert set(drawn) == {"stribeck", "hysteresis", "phase", "breakaway", "ramp",
                          "loop-position", "loop-error", "loop-force"}
    assert len(set(drawn["loop-force"])) == 5  # u, F, the stick ramps, u_ba and E13
    assert len(set(drawn["breakaway"])) >= 12  # four F̂, current, simulation, LuGre, five swept
    for plot, colors in drawn.items():
        assert too_close(colors) == [], plot
