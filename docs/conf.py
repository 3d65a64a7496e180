"""Sphinx configuration of the exudyn_atcm documentation."""

import os
import sys

import matplotlib

matplotlib.use("Agg")
sys.path.insert(0, os.path.abspath(".."))

import exudyn_atcm  # noqa: E402

project = "exudyn_atcm"
author = "exudyn_atcm developers"
copyright = "2026, exudyn_atcm developers"
release = exudyn_atcm.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "matplotlib.sphinxext.plot_directive",
]
napoleon_google_docstring = False
napoleon_numpy_docstring = True
autodoc_member_order = "bysource"
autodoc_typehints = "description"
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 100)]
exclude_patterns = ["_build"]
html_theme = "alabaster"
nitpicky = False
