"""Sphinx configuration of perturb's documentation site.

Build it (offline) from the repository root::

    python -m pip install -e ".[docs,plot,fast]"
    python -m sphinx -W -n --keep-going -b html docs docs/_build/html

Tutorials are MyST-NB text notebooks (``tutorials/*.md``) executed at every build: a cell that
raises fails the build. The gallery is sphinx-gallery (``gallery_src/plot_*.py``), the API reference
autosummary stubs generated from the numpydoc docstrings, the CLI reference the argparse tree of
``perturb.cli._parser`` rendered by ``_ext/perturb_docs.py``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import perturb

sys.path.insert(0, str(Path(__file__).resolve().parent / "_ext"))
from perturb_docs import FigureScraper  # noqa: E402 - needs _ext on the path

HERE = Path(__file__).resolve().parent
# The notebooks' kernel inherits this environment: the ``perturb`` command of *this* Python comes
# first on PATH (a venv used without activating it), and the figures render without a display.
os.environ["PATH"] = str(Path(sys.executable).parent) + os.pathsep + os.environ.get("PATH", "")
os.environ.setdefault("MPLBACKEND", "Agg")

project = "perturb"
author = "the perturb developers"
copyright = "the perturb developers, BSD-3-Clause"  # noqa: A001 - Sphinx's name
version = release = perturb.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
    "sphinx_gallery.gen_gallery",
    "sphinx-mathjax-offline",  # MathJax served from _static: the pages need no network either
    "perturb_docs",  # _ext/perturb_docs.py: the CLI reference and the constants tables
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}
root_doc = "index"
exclude_patterns = [
    "_build",
    "**.ipynb_checkpoints",
    "gallery_src",
    "gallery/*.ipynb",
    "gallery/*.py",
]
templates_path = ["_templates"]

# -- cross-references: every one must resolve (the build runs with -n -W) ---------------------------
nitpicky = True
default_role = "py:obj"
# Without intersphinx (the build is offline) names of other projects have no page to link to; our
# own names (perturb.*, problems.*) are never ignored, so a broken reference to them still fails.
nitpick_ignore_regex = [
    (
        "py:(class|obj|exc|func|meth|attr|data|mod)",
        r"(numpy|np|sympy|sp|scipy|matplotlib|attrs?)(\..*)?",
    ),
    ("py:(class|obj|exc|func|meth|attr|data|mod)", r"(enum|typing|collections|pathlib|os|abc)\..*"),
    (
        "py:(class|obj|exc)",
        r"(ValueError|TypeError|ImportError|KeyError|Warning|UserWarning|Exception)",
    ),
    ("py:(class|obj)", r"(float|int|str|bool|dict|list|tuple|callable|object|None|bytes|set)"),
]

# -- autodoc, autosummary, numpydoc ------------------------------------------------------------------
autosummary_generate = True
autosummary_imported_members = True
autodoc_typehints = "none"  # the numpydoc sections carry the types
autodoc_default_options = {"member-order": "bysource"}
numpydoc_show_class_members = False  # the class template lists the members
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks = set()

# -- MyST and MyST-NB --------------------------------------------------------------------------------
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = "force"  # every build runs every tutorial: a page cannot drift from the code
# A cell that raises fails the build through -W: the failure is a warning that carries the failing
# cell's line and its traceback, printed on screen. (raise_on_error = True failed the build behind
# Sphinx's "please report this" banner, with the cause only in a /tmp/sphinx-err-*.log file.)
nb_execution_raise_on_error = False
nb_execution_timeout = 900  # seconds per cell (the paper's reproduction is the longest, ~1 min)
nb_execution_in_temp = True  # files a tutorial writes land in a temporary folder
nb_execution_show_tb = True
nb_merge_streams = True
# The tutorials' kernels talk to the build over TCP encrypted with CurveZMQ keys the kernel
# manager provisions ("auto": when the kernelspec declares support, as ipykernel's does): without
# them ipykernel warns, once a notebook, that the traffic is plain text. MyST-NB passes no
# kernel-manager settings, so the default is set here. (IPC sockets would do too, but their
# relative path is resolved in the build's folder by the client and in the notebook's
# temporary folder by the kernel: the kernel is never reached.)
import zmq  # noqa: E402
from jupyter_client.manager import KernelManager  # noqa: E402

if zmq.has("curve"):  # libzmq built with libsodium; without it the warning stays
    KernelManager.class_traits()["transport_encryption"].default_value = "auto"

# -- sphinx-gallery: one file per figure -------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "gallery_src",
    "gallery_dirs": "gallery",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "abort_on_example_error": True,
    "reset_modules": ("matplotlib",),
    "show_memory": False,
    "run_stale_examples": True,  # every build runs every script, as it runs every tutorial
    "image_scrapers": (
        FigureScraper(),
    ),  # perturb's figures are not pyplot's (_ext/perturb_docs.py)
}

# -- HTML --------------------------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"perturb {release}"
html_static_path = ["_static"]
html_css_files = ["perturb.css"]
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 6,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_sidebars = {"index": [], "contributing-docs": []}
html_show_sourcelink = False
