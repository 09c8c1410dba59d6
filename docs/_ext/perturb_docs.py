"""Sphinx directives of perturb's site.

``.. perturb-cli::``
    the command-line reference, generated from ``perturb.cli._parser`` (``cli_rst.py``).
``.. perturb-constants:: MODULE`` (option ``:names: A B``)
    the module's public constants (default: every name of its ``__all__`` that is neither a class, a
    function nor a module), each with its value and the ``#:`` comment where it is defined.
"""

from __future__ import annotations

import importlib
import inspect
import sys

from cli_rst import cli_reference
from docutils import nodes
from docutils.parsers.rst import directives
from docutils.statemachine import StringList
from sphinx.pycode import ModuleAnalyzer
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles


class _RstDirective(SphinxDirective):
    def _parse(self, text: str) -> list[nodes.Node]:
        node = nodes.container()
        nested_parse_with_titles(
            self.state, StringList(text.splitlines(), self.get_source_info()[0]), node
        )
        return node.children


class CliDirective(_RstDirective):
    has_content = False

    def run(self) -> list[nodes.Node]:
        from perturb.cli._parser import _build_parser

        self.env.note_dependency(sys.modules["perturb.cli._parser"].__file__)
        return self._parse(cli_reference(_build_parser()))


def _attribute_doc(name: str, package: str) -> tuple[str, str] | None:
    """(module, text) of the ``#:`` comment on ``name`` in a loaded module of ``package``."""
    candidates = sorted(m for m in sys.modules if m == package or m.startswith(package + "."))
    candidates.sort(key=lambda m: m != "perturb._defaults")
    for module in candidates:
        try:
            docs = ModuleAnalyzer.for_module(module).find_attr_docs()
        except Exception:  # noqa: BLE001 - a module without source (built-in) has no comments
            continue
        if ("", name) in docs:
            text = " ".join(line.strip() for line in docs["", name] if line.strip())
            return module, text.replace("|", "\\|")  # a comment, not substitutions
    return None


class ConstantsDirective(_RstDirective):
    required_arguments = 1
    option_spec = {"names": directives.unchanged}

    def run(self) -> list[nodes.Node]:
        module_name = self.arguments[0]
        module = importlib.import_module(module_name)
        if "names" in self.options:
            names = self.options["names"].split()
        else:
            names = [
                n
                for n in module.__all__
                if not (inspect.isclass(getattr(module, n)) or callable(getattr(module, n)))
                and not inspect.ismodule(getattr(module, n))
            ]
        lines = [f".. currentmodule:: {module_name}", ""]
        for name in names:
            value = getattr(module, name)
            found = _attribute_doc(name, module_name.split(".")[0])
            if found is None:
                raise self.error(f"{module_name}.{name} has no '#:' comment where it is defined")
            source, text = found
            lines += [f".. data:: {name}"]
            if isinstance(value, int | float | str | tuple):
                lines += [f"   :value: {value!r}"]
            lines += ["", f"   {text} (Defined in ``{source}``.)", ""]
            self.env.note_dependency(sys.modules[source].__file__)
        return self._parse("\n".join(lines))


def _contexts(node) -> list[str]:
    """Where a relative name may live: the current class and module, then the enclosing scopes of
    the docstring the reference sits in (its source reads ``...:docstring of a.b.c``)."""
    module, klass = node.get("py:module"), node.get("py:class")
    prefixes = []
    if module:
        prefixes += ([f"{module}.{klass}."] if klass else []) + [f"{module}."]
    source = node.source or ""
    if "docstring of " in source:
        parts = source.rsplit("docstring of ", 1)[1].split(".")
        prefixes += [".".join(parts[:i]) + "." for i in range(len(parts), 0, -1)]
    return prefixes + [""]


def _import_target(target: str, prefixes: list[str]):
    """The Python object a reference names (relative to each context, then as written)."""
    for prefix in prefixes:
        parts = (prefix + target.lstrip("~.")).split(".")
        for split in range(len(parts), 0, -1):
            try:
                obj = importlib.import_module(".".join(parts[:split]))
            except ImportError:
                continue
            except Exception:  # noqa: BLE001 - a module that fails to import names nothing
                break
            try:
                for name in parts[split:]:
                    obj = getattr(obj, name)
            except AttributeError:
                break
            return True, obj
    return False, None


def _documented(app, env) -> dict[int, tuple[str, str]]:
    """id(object) -> (documented name, object type) of every class, function and method on a page."""
    cached = getattr(app, "_perturb_documented", None)
    if cached is not None:
        return cached
    table: dict[int, tuple[str, str]] = {}
    for name, entry in env.get_domain("py").objects.items():
        if entry.aliased or entry.objtype not in (
            "class",
            "exception",
            "function",
            "method",
            "module",
        ):
            continue
        found, obj = _import_target(name, [""])
        if found and (inspect.isclass(obj) or inspect.isroutine(obj) or inspect.ismodule(obj)):
            table.setdefault(id(obj), (name, entry.objtype))
    app._perturb_documented = table  # this build only (the app is not pickled)
    return table


def resolve_internal(app, env, node, contnode):
    """Resolve a Python reference to one of perturb's own names that has no page under that name.

    An object documented under another name (a method inherited from a documented base class, a
    class re-exported by a public package) is linked to its page; an existing object that is
    internal (a private module or helper) is shown as code. A name that does not exist in the code
    is left alone, so Sphinx reports it and the build (``-n -W``) fails.
    """
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"]
    prefixes = _contexts(node)
    if not any(p.split(".")[0] in ("perturb", "problems") for p in prefixes + [target]):
        return None
    found, obj = _import_target(target, prefixes)
    if not found:
        return None
    documented = _documented(app, env).get(id(obj))
    if documented is not None:
        name, objtype = documented
        role = {"exception": "exc", "function": "func", "method": "meth", "module": "mod"}.get(
            objtype, objtype
        )
        return env.get_domain("py").resolve_xref(
            env, node["refdoc"], app.builder, role, name, node, contnode
        )
    return nodes.literal(target, contnode.astext())


def _join_stream_chunks(outputs):
    """Join consecutive stream outputs of one name into one, by plain concatenation.

    A ``%%bash`` cell's output reaches the notebook in chunks cut anywhere in a line, and
    myst-nb's own merging (``nb_merge_streams``) ends every chunk with a newline, which breaks
    such lines ("limit-" / "cycle"). Joined here first, its merging then sees whole text.
    """
    joined = []
    for output in outputs:
        previous = joined[-1] if joined else None
        if (
            output.get("output_type") == "stream"
            and previous is not None
            and previous.get("output_type") == "stream"
            and previous.get("name") == output.get("name")
        ):
            previous["text"] = previous["text"] + output["text"]
        else:
            joined.append(output)
    return joined


def _patch_myst_nb_streams() -> None:
    from myst_nb.core import render

    merge = render.coalesce_streams
    if getattr(merge, "_perturb_joined", False):
        return

    def coalesce(outputs):
        return merge(_join_stream_chunks(outputs))

    coalesce._perturb_joined = True
    render.coalesce_streams = coalesce


def drop_object_base(app, name, obj, options, bases) -> None:
    """No "Bases: object" line: it says nothing."""
    bases[:] = [base for base in bases if base is not object]


def setup(app):
    _patch_myst_nb_streams()
    app.connect("autodoc-process-bases", drop_object_base)
    app.add_directive("perturb-cli", CliDirective)
    app.add_directive("perturb-constants", ConstantsDirective)
    app.connect("missing-reference", resolve_internal)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}


class FigureScraper:
    """sphinx-gallery image scraper for figures that live outside pyplot.

    perturb's plot functions return a ``Figure`` without registering it with pyplot (no global
    state), so the default matplotlib scraper, which asks pyplot, sees none. This one saves every
    ``Figure`` bound to a name of the example (or held in a list or tuple there) that it has not
    saved yet, in the order of the names.
    """

    def __repr__(self) -> str:  # sphinx-gallery keys its cache on the configuration's repr
        return "perturb_docs.FigureScraper()"

    def __call__(self, block, block_vars, gallery_conf):
        from matplotlib.figure import Figure
        from sphinx_gallery.scrapers import figure_rst

        namespace = block_vars["example_globals"]
        seen = namespace.setdefault("__perturb_scraped__", set())
        figures = []
        for value in list(namespace.values()):
            items = value if isinstance(value, list | tuple) else [value]
            figures += [f for f in items if isinstance(f, Figure) and id(f) not in seen]
        paths = []
        for figure, path in zip(figures, block_vars["image_path_iterator"], strict=False):
            figure.savefig(path, dpi=110)
            seen.add(id(figure))
            paths.append(path)
        return figure_rst(paths, gallery_conf["src_dir"])
