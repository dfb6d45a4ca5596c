"""The fitted model of an identification report as standalone code
(``breakaway export``): a Python module, a C99 file or JSON.

Modules: :mod:`.model` (reading and checking the report), :mod:`.reference` (the
exported discretisation evaluated with the package's functions, what the files must
reproduce), :mod:`.text` (the description every file carries), :mod:`.python` and
:mod:`.c` (the two sources).
"""

from __future__ import annotations

import json

from .. import __version__
from .c import c_source
from .model import ExportModel, ReportError, model_from_report
from .python import python_module
from .reference import steady_force, streaming_force
from .text import header_lines

#: Languages, their file name and media type.
LANGUAGES: dict[str, tuple[str, str]] = {
    "python": ("friction_model.py", "text/x-python; charset=utf-8"),
    "c": ("friction_model.c", "text/x-c; charset=utf-8"),
    "json": ("friction_model.json", "application/json"),
}


def json_document(model: ExportModel) -> str:
    """The model as JSON: parameters, effects (included and left out), units, t_0 and
    the equations and discretisation the code files implement."""
    document = {
        "format": "breakaway-friction-model",
        "version": 1,
        "exported_by": f"breakaway {__version__}",
        "kind": model.kind,
        "params": model.params(),
        "effects": list(model.effects),
        "left_out": [{"effect": effect, "reason": reason} for effect, reason in model.left_out],
        "units": {key: model.units[key] for key in (*model.params(), "x", "v", "t", "F")},
        "t_0": model.t_0,
        "description": header_lines(model),
    }
    return json.dumps(document, indent=2, ensure_ascii=False) + "\n"


def export_model(report, lang: str, s: float | None = None, t_0: float | None = None) -> str:
    """The text of the exported file for ``lang`` ('python', 'c' or 'json').

    Raises
    ------
    ReportError
        The report lacks what the export needs (the message names it).
    ValueError
        An unknown language.
    """
    if lang not in LANGUAGES:
        raise ValueError(f"lang must be one of {', '.join(LANGUAGES)}, got {lang!r}")
    model = model_from_report(report, s=s, t_0=t_0)
    render = {"python": python_module, "c": c_source, "json": json_document}[lang]
    return render(model)


__all__ = ["ExportModel", "LANGUAGES", "ReportError", "export_model", "json_document",
           "model_from_report", "steady_force", "streaming_force"]
