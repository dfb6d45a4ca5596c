"""The identification report for people (``breakaway fit FILE`` without ``--json``)."""

from __future__ import annotations


def _grouped(warnings):
    """The warnings with one sentence said once, with every parameter it is said of (the
    report keeps one warning per parameter)."""
    groups: dict[tuple[str, str], list[str]] = {}
    for w in warnings:
        groups.setdefault((w["code"], w["message"]), []).append(w.get("parameter") or "")
    return [(code, message, [p for p in parameters if p])
            for (code, message), parameters in groups.items()]


def _value(value, stderr, determined, unit):
    if value is None:
        return "n/a"
    text = f"{value:.5g}"
    if stderr is not None:
        text += f" ± {stderr:.2g}"
    text += f" {unit}".rstrip()
    if not determined:
        text += "   (not determined by the data)"
    return text


def _force(report) -> str:
    units = report.get("units", {})
    return units.get("F_ba" if report["kind"] == "breakaway" else "F", "N")


def format_report(report: dict, source: str | None = None) -> str:
    """A plain-text rendering of an identification report."""
    N = _force(report)
    units = report.get("units", {})
    lines = []
    title = f"Identification of {source}" if source else "Identification"
    lines += [title, "=" * len(title), ""]
    lines.append(f"kind: {report['kind']}, {report['n']} rows")
    method = report.get("noise_method")
    lines.append(f"noise floor: {report['noise_floor']:.4g} {N}"
                 + (f", from {method}" if method else ""))
    derivatives = report.get("derivatives")
    if derivatives:
        if derivatives["method"] == "gradient":
            lines.append("v and a: numpy.gradient (x taken as exact)")
        else:
            lines.append(f"a: a Savitzky-Golay polynomial of order {derivatives['order']} over "
                         f"{derivatives['window']} samples at the least, wider where a holds "
                         f"steady; v: {derivatives['velocity']}")
    lines.append("")
    base = report["base"]
    lines.append(f"base model: RMSE {base['rmse']:.4g} {N}, BIC {base['bic']:.1f}")
    for i, step in enumerate(report["steps"], 1):
        lines.append(f"step {i}: + {step['effect']}: RMSE {step['rmse']:.4g} {N}, "
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
        shown = _value(value, final["stderr"].get(name), final["determined"].get(name, True),
                       units.get(name, ""))
        lines.append(f"    {name:<10} {shown}")
    lines.append("")
    lines.append(f"error (RMSE, {N})     before      after")
    lines.append(f"  fit              {report['error_before']:>10.4g} {report['error_after']:>10.4g}")
    lines.append(f"  held-out         {report['heldout']['before']:>10.4g} "
                 f"{report['heldout']['after']:>10.4g}")
    lines.append(f"  noise floor      {report['noise_floor']:>10.4g}")
    lines.append("")
    lines.append("residual white: " + ("yes" if report["residual_white"] else "no"))
    if report["unexplained"]:
        lines.append("unexplained: clear structure remains that no candidate effect explains.")
    structure = [s for s in report.get("residual_structure", []) if s["strength"] >= 0.05]
    if structure:
        lines.append("the residual still depends on: " + ", ".join(
            f"{s['against']} ({100 * s['strength']:.0f} %)" for s in structure))
    if report.get("warnings"):
        lines.append("")
        lines.append("warnings:")
        for code, message, parameters in _grouped(report["warnings"]):
            named = f" ({', '.join(parameters)})" if len(parameters) > 1 else ""
            lines.append(f"  [{code}]{named} {message}")
    rejected = {e: c for e, c in report.get("candidates", {}).items() if not c["accepted"]}
    if rejected:
        lines.append("")
        lines.append("candidates not accepted:")
        for effect, verdict in rejected.items():
            lines.append(f"  {effect:<10} {verdict['reason']}")
    return "\n".join(lines) + "\n"
