"""Sphinx configuration of Breakaway's documentation (built by ``scripts/docs``).

Pages are MyST Markdown files in this folder: a new page is a new ``.md`` file listed in
``index.md``'s table of contents. The Python API reference is generated from the
package's numpydoc docstrings. The build must stay offline (no CDN, no intersphinx) and
free of warnings (``-W``): the test suite builds it (tests/docs/test_build.py).
"""

from __future__ import annotations

import breakaway

project = "Breakaway"
author = "the Breakaway developers"
copyright = "the Breakaway developers; MIT licence"
release = version = breakaway.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "numpydoc",
]
source_suffix = {".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build"]
# the generated benchmark tables are included by benchmarks.md, not pages of their own
exclude_patterns += ["benchmarks/results/*.md"]

# MyST: ::: fences for admonitions, and anchors for headings down to ### so that pages
# can link to a section (model.md#the-break-away-curve).
myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3

# numpydoc renders the Parameters/Returns sections; the class pages list their members
# through autodoc, not through autosummary tables.
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
autosummary_generate = False  # numpydoc loads autosummary; no stub pages are wanted
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the numpydoc sections give types, with units

html_theme = "pydata_sphinx_theme"
html_title = "Breakaway"
html_show_sourcelink = False
html_theme_options = {
    # served by `breakaway serve` under /guide/: the explorer is the site's root
    "external_links": [{"name": "Explorer", "url": "/"},
                       {"name": "HTTP API (OpenAPI)", "url": "/docs"}],
    # and always in the header, as icons: back to the explorer, the OpenAPI page
    # (the theme drops icon links of fewer than 3 characters: "/" is "/index.html")
    "icon_links": [
        {"name": "Explorer", "url": "/index.html", "icon": "fa-solid fa-sliders",
         "attributes": {"target": "_self"}},
        {"name": "HTTP API (OpenAPI)", "url": "/docs", "icon": "fa-solid fa-plug",
         "attributes": {"target": "_self"}},
    ],
    "header_links_before_dropdown": 5,
    "navigation_with_keys": False,
    "show_prev_next": True,
    "footer_start": ["copyright"],
    "footer_end": [],
}
# light or dark as the reader's system says, until they choose (an empty mode makes the
# theme log an error on a first visit)
html_context = {"default_mode": "auto"}
