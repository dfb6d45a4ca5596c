"""The identification report for people (``breakaway fit FILE`` without ``--json``)."""

from __future__ import annotations

_UNITS = {"Fc": "N", "Fs": "N", "V": "m/s", "delta": "", "s": "1/m", "sigma": "N·s/m",
          "Fc_neg": "N", "Fs_neg": "N", "F_offset": "N", "alpha": "1/s", "m_e": "kg",
          "A": "N", "wavelength": "m", "phase": "rad", "tau": "s", "play": "m", "zeta": "",
          "tau_d": "s"}


def _value(value, stderr):
    if value is None:
        return "n/a"
    text = f"{value:.5g}"
    if stderr is None:
        return text + " (not determined by the data)"
    return f"{text} ± {stderr:.2g}"


def format_report(report: dict, source: str | None = None) -> str:
    """A plain-text rendering of a §8 report."""
    lines = []
    title = f"Identification of {source}" if source else "Identification"
    lines += [title, "=" * len(title), ""]
    lines.append(f"kind: {report['kind']}, {report['n']} rows")
    lines.append(f"noise floor (model-free): {report['noise_floor']:.4g} N")
    lines.append("")
    base = report["base"]
    lines.append(f"base model: RMSE {base['rmse']:.4g} N, BIC {base['bic']:.1f}")
    for i, step in enumerate(report["steps"], 1):
        lines.append(f"step {i}: + {step['effect']}: RMSE {step['rmse']:.4g} N, "
                     f"BIC {step['bic']:.1f}")
        lines.append(f"    evidence: {step['evidence']}")
    if not report["steps"]:
        lines.append("no effect added: "
                     + ("the base model explains the data down to the noise."
                        if report["residual_white"] else "no candidate passed the tests."))
    lines.append("")
    effects = ", ".join(report["effects"]) or "none"
    lines.append(f"effects found: {effects}")
    final = report["final"]
    lines.append("final parameters:")
    for name, value in final["params"].items():
        unit = _UNITS.get(name, "")
        lines.append(f"    {name:<10} {_value(value, final['stderr'].get(name))} {unit}".rstrip())
    lines.append("")
    lines.append("error (RMSE, N)      before      after")
    lines.append(f"  fit              {report['error_before']:>10.4g} {report['error_after']:>10.4g}")
    lines.append(f"  held-out         {report['heldout']['before']:>10.4g} "
                 f"{report['heldout']['after']:>10.4g}")
    lines.append(f"  noise floor      {report['noise_floor']:>10.4g}")
    lines.append("")
    lines.append("residual white: " + ("yes" if report["residual_white"] else "no"))
    if report["unexplained"]:
        lines.append("unexplained: clear structure remains that no candidate effect explains.")
    return "\n".join(lines) + "\n"
