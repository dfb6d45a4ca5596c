"""The page's units from one source (frontend/js/page/units.js): linear (N, m) until the
parameters of a fit of rotary data are used, then the data's (N·m, rad or deg) in every
label, axis, tooltip, sentence, table and export; a preset in SI units returns them to
linear, and a link keeps them."""

from __future__ import annotations

import re
from urllib.parse import parse_qs, urlparse

import pytest

from breakaway.identify.csvdata.dataset import _ROTARY_UNIT, unit_of
from breakaway.identify.synthetic import make_dataset, to_csv
from breakaway.plan.checks import _ramps_record

pytestmark = pytest.mark.browser

PANEL = "#data-panel"
#: The rotary units' own "N·m" and "kg·m²" are not the linear N, m and kg.
ROTARY_PARTS = ("N·m", "kg·m²")


def linear_units(text: str) -> list[str]:
    """The linear units (N, m, kg and those made of them: m/s, N·s/m, …) that `text`
    gives a quantity: in brackets ("[N]") or after a number ("2.6 N", "±0.004 m")."""
    found = re.findall(r"\[([^\]]*)\]", text)
    found += re.findall(r"(?<![\w.])[-−+±]?\d[\d.]*(?:e[-+]?\d+)?\s+([A-Za-zµ°][\w·/()²³^°µ]*)", text)
    linear = []
    for unit in found:
        rest = unit
        for part in ROTARY_PARTS:
            rest = rest.replace(part, "")
        if any(token in ("N", "m", "kg") for token in re.split(r"[·/()²³^\s,]+", rest)):
            linear.append(unit)
    return linear


def test_the_finder_finds_linear_units_and_passes_rotary_ones():
    assert len(linear_units("Fs = 2.6 N, ±0.00429 m, Ki = 1560 N/(m·s), V [m/s], m [kg]")) == 5
    assert linear_units("Fs = 2.6 N·m, ±0.00429 rad, Ki = 1560 N·m/(rad·s), V [rad/s], m [kg·m²], "
                        "3 break-aways in 2.5 s, s [1/deg]") == []


#: Every text of the page a person reads: its visible text, labels, names and titles of
#: controls, and in every plot its axis titles, trace names and tooltips.
TEXTS = """() => {
  const out = [['page', document.body.innerText]];
  for (const el of document.querySelectorAll('label, [aria-label], option, th, legend, figcaption')) {
    const where = el.tagName === 'OPTION' ? `${el.parentElement.id} option` : el.id || el.tagName;
    out.push([where, `${el.getAttribute('aria-label') ?? ''} ${el.getAttribute('title') ?? ''} ${el.textContent}`]);
  }
  for (const gd of document.querySelectorAll('.js-plotly-plot')) {
    const layout = gd.layout ?? {};
    for (const key of Object.keys(layout)) {
      if (/^[xy]axis/.test(key)) out.push([`${gd.id} ${key}`, String(layout[key].title?.text ?? '')]);
    }
    for (const trace of gd.data ?? []) out.push([`${gd.id} trace`, `${trace.name ?? ''} ${trace.hovertemplate ?? ''}`]);
  }
  return out;
}"""


def test_a_rotary_fit_carried_into_the_loop_speaks_the_rigs_units(explorer):
    data, _ = make_dataset("timeseries", (), seed=5)
    text = "# units: rotary\n" + to_csv(data)
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_label("Data file", exact=True).set_input_files(
        {"name": "joint.csv", "mimeType": "text/csv", "buffer": text.encode()})
    page.wait_for_selector(f'{PANEL}[data-state="done"], {PANEL}[data-state="error"]', timeout=60_000)
    assert page.locator(PANEL).get_attribute("data-state") == "done"
    page.get_by_role("button", name="Use these parameters", exact=True).click()
    explorer.ready()
    assert explorer.state()["units"] == "rotary"
    assert "Set Fc = " in page.locator("#use-note").inner_text()
    assert re.search(r"Fc = [\d.]+ N·m", page.locator("#use-note").inner_text())
    page.get_by_role("button", name="Try this model in a control loop", exact=True).click()
    explorer.ready()
    page.evaluate("window.breakaway.rampReady()")
    page.evaluate("window.breakaway.loopReady()")
    # the controls are found by their labels in the rig's units
    assert page.get_by_label("Fc [N·m]", exact=True).is_visible()
    assert page.get_by_label("Kp [N·m/rad]", exact=True).is_visible()
    loop = page.locator("#loop-explain").inner_text()
    assert " rad" in loop and "N·m" in loop
    found = {}
    for where, said in page.evaluate(TEXTS):
        for unit in linear_units(said):
            found.setdefault(unit, where)
    # the SI presets' descriptions (the lab stage's "Fc = 2 N") are in their own units:
    # choosing one returns the page to them (below)
    assert {unit: where for unit, where in found.items() if where != "preset option"} == {}
    assert parse_qs(urlparse(page.url).query)["units"] == ["rotary"]
    # a link keeps the units; a preset in SI units returns the page to linear ones
    explorer.open(f"?{urlparse(page.url).query}")
    assert page.get_by_label("V [rad/s]", exact=True).is_visible()
    page.get_by_label("Preset", exact=True).select_option("lab-stage")
    explorer.ready()
    assert explorer.state()["units"] == "linear"
    assert page.get_by_label("V [m/s]", exact=True).is_visible()


def test_the_planner_asks_and_answers_in_the_rigs_units(explorer):
    # break-away forces of a rotary joint at rates too high to see V and δ: the planner
    # under the report asks for the rig's limits and proposes ramps in N·m and rad
    text = "# units: rotary\n" + to_csv(_ramps_record(1, 40.0, 300.0, 0.005))
    explorer.open("?sim=0")
    page = explorer.page
    page.get_by_label("Data file", exact=True).set_input_files(
        {"name": "joint-ramps.csv", "mimeType": "text/csv", "buffer": text.encode()})
    page.wait_for_selector(f'{PANEL}[data-state="done"]', timeout=60_000)
    assert page.get_by_role("region", name="Plan the next experiment").is_visible()
    page.get_by_label("Largest force u_max [N·m]", exact=True).fill("3")
    page.get_by_label("Runs", exact=True).fill("10")
    page.get_by_label("Kind of runs").select_option("steady")
    assert page.get_by_label("Slowest speed held v_min [rad/s]", exact=True).is_visible()
    assert page.get_by_label("Largest speed v_max [rad/s]", exact=True).is_visible()
    page.get_by_label("Kind of runs").select_option("sine")
    assert page.get_by_label("Travel [rad]", exact=True).is_visible()
    page.get_by_label("Kind of runs").select_option("ramps")
    page.get_by_role("button", name="Plan", exact=True).click()
    page.locator("#plan-results").wait_for(state="visible")
    design = page.locator("#plan-design").inner_text()
    assert re.search(r"at k = [\d.,() ×]+ N·m/s, each up to at most [\d.]+ N·m", design), design
    box = page.evaluate("""() => [...document.querySelectorAll('#plan-box label, #plan-box')]
        .map((el) => el.innerText)""")
    assert [unit for said in box for unit in linear_units(said)] == []


@pytest.mark.parametrize("units,angle", [("rotary", "rad"), ("rotary-deg", "deg")])
def test_the_pages_units_are_the_servers(explorer, units, angle):
    # the page's table of rotary units is the engine's (csvdata unit_of), plus the loop's gains
    explorer.open("?sim=0")
    linear = [*_ROTARY_UNIT, "s", "Hz", ""]
    shown = explorer.page.evaluate("""async ([linear, units]) => {
      const { unit } = await import('/js/page/units.js');
      return linear.map((u) => unit(u, { units }));
    }""", [linear, units])
    assert shown == [unit_of(u, True, angle) for u in linear]
    gains = explorer.page.evaluate("""async (units) => {
      const { unit } = await import('/js/page/units.js');
      return ['N/m', 'N/(m·s)', 'N²·s/m²'].map((u) => unit(u, { units }));
    }""", units)
    assert gains == [g.replace("rad", angle) for g in ("N·m/rad", "N·m/(rad·s)", "(N·m)²·s/rad²")]
