"""Sphinx configuration of crankgen's documentation (`make docs`: docs/_build/html, warnings are errors).

Pages are MyST Markdown; the API reference is autodoc over the public names of `crankgen`; the
gallery is sphinx-gallery (docs/examples/*.py, run at every build); `{crankgen-run}` blocks
(docs/_ext/crankgen_docs.py) run their code at build time and show its output and figures; the
command line and the CSV columns are generated from the parser and the declaration.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

from crankgen import __version__ as VERSION  # noqa: E402

project = "crankgen"
author = "the crankgen authors"
copyright = "the crankgen authors"
release = version = VERSION

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx_gallery.gen_gallery",
    "crankgen_docs",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "_generated", "reference/_generated", "gallery/*.md5", "examples/README.md", "examples/GALLERY_HEADER.rst", "Thumbs.db", ".DS_Store"]
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
nitpicky = False

autodoc_member_order = "bysource"
autodoc_default_options = {"members": False}
autodoc_typehints = "none"
napoleon_numpy_docstring = True
napoleon_google_docstring = False

# The gallery: every docs/examples/plot_*.py runs at every build; an example that fails fails the
# build (abort_on_example_error).  Each is sized to run in seconds on 2 cores and names the
# full-size command in its text.
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "gallery",
    "filename_pattern": r"plot_",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "show_memory": False,
    "show_signature": False,
    "reset_modules": ("matplotlib",),
    "capture_repr": (),
}

html_theme = "alabaster"
html_title = f"crankgen {VERSION}"
html_static_path = ["_static"]
html_css_files = ["crankgen.css"]
html_theme_options = {
    "description": "Dynamics of flexible mechanisms",
    "fixed_sidebar": False,
    "page_width": "1240px",
    "sidebar_width": "240px",
    "show_relbars": True,
}
html_sidebars = {"**": ["about.html", "navigation.html", "searchbox.html"]}
html_show_sourcelink = False
html_last_updated_fmt = None
# the build is reproducible: no timestamps in the pages
html_show_sphinx = False

