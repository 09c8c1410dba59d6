"""The documentation site: its CLI reference, its cross-references, and the whole build (issue 20).

The build itself is slow (every tutorial and gallery script is executed): it runs with
``pytest -m slow``. It is the README's command, with warnings as errors (``-W``) and nitpicky
cross-references (``-n``), then every internal link and anchor of the built pages is resolved.
"""

from __future__ import annotations

import doctest
import importlib.util
import os
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

from perturb.cli._parser import _build_parser

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"


def _cli_rst_module():
    spec = importlib.util.spec_from_file_location("cli_rst", DOCS / "_ext" / "cli_rst.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _subcommands(parser):
    import argparse

    action = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return action.choices


def test_cli_reference_names_every_command_and_option():
    parser = _build_parser()
    text = _cli_rst_module().cli_reference(parser)
    for name, command in _subcommands(parser).items():
        assert f".. program:: perturb {name}\n" in text, name
        section = text.split(f".. program:: perturb {name}\n", 1)[1].split(".. program::", 1)[0]
        for action in command._actions:
            if action.help == "show this help message and exit":
                continue
            for flag in action.option_strings or [action.metavar or action.dest]:
                assert f".. option:: {flag}" in section, f"perturb {name}: {flag}"


def test_reference_page_examples_run():
    """The ``>>>`` lines written into the reference pages themselves (not docstrings)."""
    for page in sorted((DOCS / "reference").glob("*.rst")):
        result = doctest.testfile(str(page), module_relative=False, optionflags=doctest.ELLIPSIS)
        assert result.failed == 0, page.name


def _build(source: Path, out: Path, builder: str = "html") -> subprocess.CompletedProcess:
    """The README's build command (needs the docs extra: skipped without it)."""
    for module in ("sphinx", "myst_nb", "numpydoc", "pydata_sphinx_theme", "sphinx_gallery"):
        pytest.importorskip(module, reason="needs the docs extra: pip install -e '.[docs]'")
    command = [sys.executable, "-m", "sphinx", "-W", "-n", "--keep-going", "-b", builder]
    command += ["-d", str(out / ".doctrees"), str(source), str(out / builder)]
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=3600)


def _tiny_site(tmp_path: Path, body: str) -> Path:
    source = tmp_path / "src"
    source.mkdir(parents=True)
    (source / "conf.py").write_text(
        "import sys\n"
        f"sys.path.insert(0, {str(DOCS / '_ext')!r})\n"
        "extensions = ['sphinx.ext.autodoc', 'perturb_docs']\n"
        "autodoc_typehints = 'none'\n"
    )
    (source / "index.rst").write_text("Tiny\n====\n\n" + body + "\n")
    return source


def test_a_reference_to_a_name_that_does_not_exist_fails_the_build(tmp_path):
    """The site's resolver (``_ext/perturb_docs.py``) turns references to perturb's internal
    names into code, and links those documented under another name; it must not hide a
    reference to a name that does not exist."""
    good = _tiny_site(
        tmp_path / "good",
        ".. autofunction:: perturb.validate\n\n"
        "See :func:`perturb.validate`, :class:`perturb.oracle.base.Run` and "
        ":mod:`perturb.oracle.base`.",
    )
    result = _build(good, tmp_path / "good" / "out")
    assert result.returncode == 0, result.stderr[-2000:]
    bad = _tiny_site(tmp_path / "bad", "See :func:`perturb.no_such_function`.")
    result = _build(bad, tmp_path / "bad" / "out")
    assert result.returncode != 0
    assert "perturb.no_such_function" in result.stderr


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids: set[str] = set()
        self.links: list[str] = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("name"):
            self.ids.add(attrs["name"])
        for key in ("href", "src"):
            if attrs.get(key) and not (tag == "link" and attrs.get("rel") == "preload"):
                self.links.append(attrs[key])


def _parse(page: Path) -> _Links:
    parser = _Links()
    parser.feed(page.read_text(errors="replace"))
    return parser


@pytest.mark.slow
def test_the_site_builds_with_warnings_as_errors_and_its_links_resolve(tmp_path):
    result = _build(DOCS, tmp_path)
    assert result.returncode == 0, (result.stdout[-3000:], result.stderr[-3000:])
    html = tmp_path / "html"
    expected = ["index", "getting-started", "contributing-docs", "reference/cli", "gallery/index"]
    expected += [f"tutorials/{p.stem}" for p in (DOCS / "tutorials").glob("*.md")]
    expected += [f"gallery/{p.stem}" for p in (DOCS / "gallery_src").glob("plot_*.py")]
    expected += [
        "reference/generated/perturb.PoincareMethod",
        "reference/generated/perturb.validate",
    ]
    for name in expected:
        assert (html / f"{name}.html").is_file(), name
    # every internal link and anchor resolves
    pages = {page: _parse(page) for page in html.rglob("*.html") if "_static" not in page.parts}
    broken = []
    for page, parsed in pages.items():
        for link in parsed.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith(("mailto:", "javascript:", "data:")):
                continue
            target = (page.parent / unquote(parts.path)).resolve() if parts.path else page
            if not target.exists():
                broken.append(f"{page.relative_to(html)} -> {link}")
            elif parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else _parse(target).ids
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{page.relative_to(html)} -> {link} (no such anchor)")
    assert not broken, broken[:20]
    # the tutorials' figures were rendered (a notebook figure is an embedded PNG file)
    for page in (html / "tutorials").glob("*.html"):
        if page.stem != "index" and page.stem != "new-problem":
            assert any(link.endswith(".png") for link in pages[page].links), page.name


def test_every_plot_kind_has_a_gallery_figure():
    """A new ``plot_*`` function of ``perturb.report.plots`` needs its ``docs/gallery_src`` file
    (``animate_orientation`` writes the orientation picture as a GIF: its figure is
    ``plot_orientation``'s)."""
    import perturb.report.plots as plots

    scripts = "\n".join(p.read_text() for p in (DOCS / "gallery_src").glob("plot_*.py"))
    kinds = [name for name in plots.__all__ if name.startswith("plot_")]
    assert len(kinds) >= 7
    missing = [name for name in kinds if f"{name}(" not in scripts]
    assert not missing, f"no gallery script calls {missing}"
