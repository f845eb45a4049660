"""Sphinx configuration of tactcad's documentation site (make docs).

MyST Markdown pages; the reference pages are generated from the code when the
site is built (_ext/tactcad_reference.py); equations are MathML written at
build time (_ext/mathml_math.py), so the site opens from file:// with no
network. Warnings are errors (make docs runs sphinx -W).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))  # a checkout's tactcad, installed or not

import tactcad  # noqa: E402

project = "tactcad"
author = "The tactcad authors"
copyright = "the tactcad authors, Apache-2.0"
release = tactcad.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",  # the docstrings' Args / Returns / Raises sections
    "mathml_math",
    "tactcad_reference",
]

source_suffix = {".md": "markdown"}
# option names stay as typed (--set, not an en dash), quotes straight
smartquotes = False
root_doc = "index"
# _generated: the reference pages' generated parts, included by the pages themselves
exclude_patterns = ["_build", "_generated", "Thumbs.db", ".DS_Store"]

myst_enable_extensions = ["dollarmath", "amsmath", "deflist", "colon_fence"]
myst_heading_anchors = 3
myst_dmath_double_inline = True

html_math_renderer = "mathml"
html_theme = "alabaster"
html_title = f"tactcad {release}"
html_static_path = ["_static"]
html_css_files = ["tactcad.css"]
html_theme_options = {
    "description": "CAD for spring-based tactile sensor arrays",
    "fixed_sidebar": True,
    "page_width": "1240px",
    "body_max_width": "none",
    "sidebar_width": "250px",
    "show_relbars": True,
}
html_sidebars = {"**": ["about.html", "navigation.html", "relations.html", "searchbox.html"]}
html_show_sourcelink = False

autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False}
napoleon_google_docstring = True
napoleon_numpy_docstring = False
# Attributes sections as fields of their class, not a second description of each attribute
napoleon_use_ivar = True
# pages build in the same order and bytes on every machine
html_last_updated_fmt = None
