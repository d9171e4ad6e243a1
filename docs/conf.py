"""Sphinx configuration of dyade's documentation site.

Build (from the repository, with the docs extra: pip install -e ".[docs,plot,test]"):

    sphinx-build -W -b html docs docs/_build/html

The getting-started page and the gallery are executed at build time (myst-nb); a cell
that raises fails the build (-W: warnings are errors)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "docs"))
os.environ.setdefault("MPLBACKEND", "Agg")

import dyade  # noqa: E402

project = "dyade"
author = "the dyade developers"
copyright = "dyade developers, MIT licence"
version = release = dyade.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}  # autosummary writes .rst
exclude_patterns = ["_build", "jupyter_execute", "**.ipynb_checkpoints"]
root_doc = "index"

# MyST: GitHub-flavoured tables, $…$ maths, ::: fences; headings get anchors
myst_enable_extensions = ["colon_fence", "dollarmath", "deflist"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]  # moved README prose starts some pages at ###

# myst-nb: run every notebook page at build time, from the repository (the examples
# read the shipped mechanisms by relative path); a cell that raises fails the build
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 300
nb_execution_show_tb = True
nb_merge_streams = True

# API reference: autosummary pages from numpydoc docstrings
autosummary_generate = True
templates_path = ["_templates"]  # a class page: its docstring (numpydoc lists the fields)
autosummary_imported_members = True
autodoc_typehints = "none"
autodoc_default_options = {"members": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

html_theme = "pydata_sphinx_theme"
html_title = f"dyade {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_static_path: list[str] = []
html_last_updated_fmt = None
