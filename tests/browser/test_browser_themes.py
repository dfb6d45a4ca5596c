"""Presentation mode, dark mode and print: how the explorer looks in a lecture hall."""

from __future__ import annotations

import pytest

from browser_model import until

pytestmark = pytest.mark.browser

PLOTS = ("stribeck", "hysteresis", "phase", "breakaway", "ramp", "loop-position", "loop-error",
         "loop-force")


def layout(explorer, plot: str, path: str):
    return explorer.page.evaluate(
        f"(id) => document.getElementById('plot-' + id).layout.{path}", plot)


def test_presentation_mode_from_the_url_and_the_toggle(explorer):
    explorer.open("?sim=0&present=1")
    explorer.page.evaluate("window.breakaway.loopReady()")
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


#: Font sizes of every text on the page that is shown: each element with text of its
#: own (superscripts and subscripts of an equation aside), and Plotly's tick labels,
#: legend entries and axis titles.
TEXT_SIZES = """() => {
  const out = [];
  for (const element of document.querySelectorAll('body *')) {
    if (element.closest('svg, sup, sub, script, style, .skip-link, [hidden]')) continue;
    const own = [...element.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim());
    const field = element.matches('input:not([type="checkbox"]):not([type="range"]), select')
      || (element.matches('button') && element.textContent.trim() !== '');
    if ((!own && !field) || !element.getClientRects().length) continue;
    if (getComputedStyle(element).visibility !== 'visible') continue;
    out.push([element.tagName + '#' + element.id + '.' + element.className, parseFloat(getComputedStyle(element).fontSize)]);
  }
  for (const text of document.querySelectorAll(
      '#plots .xtick text, #plots .ytick text, #plots .y2tick text, #plots .legendtext, #plots .xtitle, #plots .ytitle')) {
    if (!text.closest('.plot')) continue;
    out.push(['plotly ' + text.getAttribute('class') + ' ' + text.textContent, parseFloat(getComputedStyle(text).fontSize)]);
  }
  return out;
}"""


def test_presentation_mode_sets_every_text_from_18_px(explorer):
    explorer.page.set_viewport_size({"width": 1920, "height": 1080})
    explorer.open("?sim=1&present=1")
    explorer.sim_ready()
    explorer.page.evaluate("window.breakaway.rampReady()")
    sizes = explorer.page.evaluate(TEXT_SIZES)
    assert len(sizes) > 150
    assert [entry for entry in sizes if entry[1] < 18] == []
    # without presentation mode the same page has smaller text
    explorer.page.get_by_label("Presentation mode (large type, heavy lines)").uncheck()
    explorer.ready()
    assert min(size for _, size in explorer.page.evaluate(TEXT_SIZES)) < 18


def test_dark_mode_follows_the_system(explorer):
    explorer.page.emulate_media(color_scheme="dark")
    explorer.open("?sim=0")
    background = explorer.page.evaluate("getComputedStyle(document.documentElement).backgroundColor")
    red, green, blue = (int(v) for v in background[background.index("(") + 1:-1].split(",")[:3])
    assert max(red, green, blue) < 60
    assert layout(explorer, "stribeck", "paper_bgcolor") == "rgba(0,0,0,0)"
    assert layout(explorer, "stribeck", "font.color") == "#e4e7eb"
    # black ink (the simulated path) turns light, where black would vanish
    explorer.page.evaluate("window.breakaway.rampReady()")
    colors = explorer.page.evaluate(
        "document.getElementById('plot-phase').data.map((t) => t.line && t.line.color)")
    assert "#111" not in colors and "#e4e7eb" in colors


def test_print_shows_the_plots_without_the_controls(explorer):
    explorer.open("?sim=0")
    explorer.page.emulate_media(media="print")
    assert not explorer.page.locator("#controls").is_visible()
    assert explorer.page.locator("#plot-breakaway").is_visible()
    assert explorer.page.locator("#ba-explain").is_visible()


OKABE_ITO = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#f0e442"}


def test_the_break_away_curves_differ_by_more_than_red_and_green(explorer):
    explorer.open("?sim=0")
    curves = explorer.page.evaluate(
        """() => document.getElementById('plot-breakaway').data
             .filter((t) => t.name.startsWith('F̂ = '))
             .map((t) => [t.line.color, t.line.dash])""")
    assert len(curves) == 4
    assert {color for color, _ in curves} <= OKABE_ITO
    # the two Okabe–Ito hues nearest to red and green also differ by dash
    styles = dict(curves)
    assert styles["#d55e00"] != styles["#009e73"]


def test_every_tooltip_names_its_units(explorer):
    explorer.open("?sim=1")
    explorer.sim_ready()
    explorer.page.evaluate("window.breakaway.loopReady()")
    templates = explorer.page.evaluate(
        """() => ['stribeck', 'hysteresis', 'phase', 'breakaway', 'ramp', 'loop-position',
                  'loop-error', 'loop-force'].flatMap((id) =>
             document.getElementById('plot-' + id).data
               .filter((t) => t.hoverinfo !== 'skip')
               .map((t) => [id, t.name, t.hovertemplate || null]))""")
    assert len(templates) >= 14 + 7
    for plot, name, template in templates:
        assert template, f"{plot}: {name} has Plotly's default tooltip"
        assert any(unit in template for unit in (" N", " m/s", " m<", " s<", " N/s")), (plot, name)
        # 3–4 significant digits, never Plotly's default 7
        assert all(spec in {".3g", ".4g", ".3f"} for spec in _formats(template)), (plot, name)


def _formats(template: str) -> list[str]:
    import re
    return re.findall(r"%\{[a-z]+:([^}]+)\}", template)


def test_the_phase_legend_sits_below_the_axes(explorer):
    explorer.open("?sim=0")
    legend = layout(explorer, "phase", "legend")
    assert legend["orientation"] == "h" and legend["y"] < 0
    below = explorer.page.evaluate(
        """() => { const gd = document.getElementById('plot-phase');
             const top = gd.getBoundingClientRect().top, size = gd._fullLayout._size;
             return gd.querySelector('.legend').getBoundingClientRect().top - top - (size.t + size.h); }""")
    assert below > 0  # the legend starts under the plot area, clear of both axes


#: Tick labels are drawn where they fall (Plotly is told not to measure and hide the ones
#: past an axis end), so every one must fit inside its plot.
TICKS_OUTSIDE = """() => {
  const outside = [];
  for (const div of document.querySelectorAll('#plots .js-plotly-plot')) {
    const plot = div.getBoundingClientRect();
    for (const label of div.querySelectorAll('.xtick text, .ytick text, .y2tick text')) {
      const box = label.getBoundingClientRect();
      if (box.width && (box.right > plot.right + 0.5 || box.left < plot.left - 0.5)) {
        outside.push(`${div.id}: ${label.textContent}`);
      }
    }
  }
  return outside;
}"""


@pytest.mark.parametrize("viewport", [(390, 844), (1280, 800), (1920, 1080)])
@pytest.mark.parametrize("present", [0, 1])
def test_every_tick_label_fits_inside_its_plot(explorer, viewport, present):
    explorer.page.set_viewport_size({"width": viewport[0], "height": viewport[1]})
    explorer.open(f"?sim=0&present={present}")
    assert explorer.page.locator("#plots .xtick text").count() > 0
    assert explorer.page.evaluate(TICKS_OUTSIDE) == []


#: Each plot's drawing against its box and its card: [id, svg width − box width, the
#: drawing inside its card].
FITS = """() => [...document.querySelectorAll('.plot, .fit-plot')].filter((p) => p.offsetParent).map((p) => {
  const card = p.closest('.plot-card').getBoundingClientRect();
  const svg = p.querySelector('svg.main-svg');
  const box = svg ? svg.getBoundingClientRect() : null;
  return [p.id, box ? Math.round(box.width - p.clientWidth) : null,
          Boolean(box) && box.left >= card.left - 1 && box.right <= card.right + 1
            && box.top >= card.top - 1 && box.bottom <= card.bottom + 1];
})"""


def laid_out(explorer) -> list:
    """Every plot's fit once the page has laid them out at their boxes' sizes."""
    until(explorer.page, f"({FITS})().every(([, gap]) => gap !== null && Math.abs(gap) <= 1)", seconds=10)
    return explorer.page.evaluate(FITS)


@pytest.mark.parametrize("viewport", [(390, 844), (1280, 800), (1920, 1080)])
def test_presentation_mode_toggled_in_place_lays_every_plot_out_in_its_card(explorer, viewport):
    explorer.page.set_viewport_size({"width": viewport[0], "height": viewport[1]})
    explorer.open("?sim=0")
    explorer.page.evaluate("window.breakaway.loopReady()")
    before = {plot: width for plot, width, _ in explorer.page.evaluate(
        "() => [...document.querySelectorAll('.plot')].map((p) => [p.id, 0, p.clientWidth])")}
    explorer.page.get_by_label("Presentation mode (large type, heavy lines)").check()
    explorer.ready()
    fits = laid_out(explorer)
    assert len(fits) >= 8
    assert all(inside for _, _, inside in fits), fits
    # and every card inside the page, which never scrolls sideways
    assert explorer.page.evaluate("document.documentElement.scrollWidth") <= viewport[0]
    # the boxes did change (another grid, taller plots): a drawing at its old size would not fit
    after = explorer.page.evaluate(
        "() => Object.fromEntries([...document.querySelectorAll('.plot')].map((p) => [p.id, p.clientWidth]))")
    if viewport[0] > 720:
        assert any(after[plot] != width for plot, width in before.items())


def test_a_phone_turned_lays_the_plots_out_anew(explorer):
    explorer.page.set_viewport_size({"width": 390, "height": 844})
    explorer.open("?sim=0")
    explorer.page.set_viewport_size({"width": 844, "height": 390})
    fits = laid_out(explorer)
    assert all(inside for _, _, inside in fits), fits
    explorer.page.set_viewport_size({"width": 390, "height": 844})
    assert all(inside for _, _, inside in laid_out(explorer))
