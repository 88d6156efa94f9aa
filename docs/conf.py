"""Sphinx configuration of dhsym's documentation (``make docs``; scripts/build_docs.py)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = Path(os.environ.get("DHSYM_DOCS_ROOT", HERE.parent)).resolve()
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(ROOT))

import dhsym_docs  # noqa: E402

from dhsym._version import __version__  # noqa: E402

project = "dhsym"
author = "dhsym developers"
copyright = "dhsym developers, MIT licence"  # noqa: A001 - Sphinx's own name
version = release = __version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_copybutton",
    "dhsym_docs",
]

dhsym_repo_root = str(ROOT)
exclude_patterns = ["_build", "_ext", "**.ipynb_checkpoints", "README.md"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb", ".rst": "restructuredtext"}
root_doc = "index"
smartquotes = False  # "--format" and "..." in help texts and code-like prose stay as typed

# MyST: $…$ and $$…$$ maths, ::: fences, anchors for ## headings (links like page.md#anchor).
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist", "attrs_inline"]
myst_heading_anchors = 3
# $$…$$ inside a paragraph is display maths too: the derivations dhsym writes as Markdown
# (the notebooks' outputs) put a display right after the sentence that introduces it.
myst_dmath_double_inline = True

# The notebooks are committed executed (the test suite runs every one and fails on any
# error or warning, and checks each .ipynb against its jupytext source): render them as
# they are, so the build stays fast and runs nothing.
nb_execution_mode = "off"
nb_merge_streams = True
# dhsym's objects show themselves as Markdown with $…$ maths and pipe tables (their
# _repr_markdown_): parse those outputs with MyST and this page's extensions (dollarmath,
# tables), not as bare CommonMark, which leaves the maths and the tables as raw text.
nb_render_markdown_format = "myst"
nb_ipywidgets_js: dict[str, dict[str, str]] = {}  # no CDN: widgets show their static text
# ... and their picture: a widget stored without its state (dhsym's notebooks keep none)
# shows its static fallback (robot.view()'s PNG), not an empty placeholder. The live 3D
# views are the pages of _static/views/ (dhsym_docs writes them).
nb_mime_priority_overrides = [("html", "application/vnd.jupyter.widget-view+json", None)]

# API: autodoc imports dhsym's modules (nothing else runs); numpydoc reads the docstrings.
autosummary_generate = False
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "signature"
# Three rooms each have a ``Step`` (explain.data, geometry.chains, ik.steps): an annotation
# that autodoc cannot evaluate (a Protocol's methods) names it bare, and Sphinx then warns that
# the short name has several targets. Only that ambiguity warning is silenced; unresolved
# references and every other warning still fail the build.
suppress_warnings = ["ref.python"]
autodoc_preserve_defaults = True
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = False

# MathJax 2 from Debian's libjs-mathjax, copied into _static/mathjax by dhsym_docs: no CDN.
mathjax_path = dhsym_docs.MATHJAX_PATH
mathjax2_config = {
    "tex2jax": {
        "inlineMath": [["\\(", "\\)"]],
        "displayMath": [["\\[", "\\]"]],
        # MyST marks the page tex2jax_ignore and its maths with the class "math"
        "processClass": "tex2jax_process|mathjax_process|math|output_area",
        "ignoreClass": "tex2jax_ignore|mathjax_ignore|document",
        "processRefs": False,
        "processEnvironments": False,
    },
    "CommonHTML": {"linebreaks": {"automatic": False}},
    "menuSettings": {"zoom": "None"},
}

html_theme = "pydata_sphinx_theme"
html_title = f"dhsym {version}"
html_static_path: list[str] = []
html_last_updated_fmt = None
html_show_sourcelink = True
html_copy_source = True
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "header_links_before_dropdown": 7,
    "navbar_end": ["theme-switcher", "navbar-icon-links"],
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
}
html_context = {"default_mode": "light"}
copybutton_prompt_text = r">>> |\.\.\. |\$ "
copybutton_prompt_is_regexp = True

# "Edit this page" links, when the site is built for a published repository:
# DHSYM_DOCS_GITHUB=owner/repo[@branch] make docs
_github = os.environ.get("DHSYM_DOCS_GITHUB", "")
if _github:
    _repo, _, _branch = _github.partition("@")
    _user, _, _name = _repo.partition("/")
    html_context.update(
        github_user=_user, github_repo=_name, github_version=_branch or "main", doc_path="docs"
    )
    html_theme_options["use_edit_page_button"] = True
    html_theme_options["icon_links"] = [
        {"name": "GitHub", "url": f"https://github.com/{_repo}", "icon": "fa-brands fa-github"}
    ]
