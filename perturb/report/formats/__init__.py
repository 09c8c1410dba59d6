"""Output formats as a registry: a format is one entry — its name, and a writer for each kind of
result it takes.

Each module of this package named ``*_format.py`` defines ``FORMAT``, a :class:`Format`; the
package finds them itself, so adding a format is one file. The CLI reads every ``--format``
choice list from :func:`choices` and prints :func:`write`'s text; nothing else in the CLI knows a
format by name. Writers import what they format lazily: building the parser (``perturb --help``)
imports this package and the format modules only.

Kinds of result (what a writer is given):

``problems``
    ``[(name, summary, parameter_specs), ...]`` (``perturb list``)
``solution``
    :class:`perturb.report.state.StateOutput` (``perturb solve``)
``validation``, ``work-precision``, ``response``
    the result object (:class:`~perturb.validation.ValidationReport`, ...)
``families``
    :class:`perturb.report.families.FamiliesOutput`
``phase``
    :class:`perturb.report.phase.PhaseOutput`
``reproduction``
    :class:`perturb.report.formats.base.Reproduced`
``sweep``
    :class:`perturb.report.sweep.SweepOutput`
``basins``
    :class:`perturb.report.dynamics.BasinsOutput` (``perturb basins``)
``transient``, ``ramp``
    :class:`~perturb.dynamics.Transient`, :class:`~perturb.dynamics.Ramp`
``failure``
    a dict: what a failed ``perturb solve`` writes (JSON only; other formats write nothing)

Examples
--------
>>> from perturb.report.formats import choices
>>> choices("validation")
['table', 'json', 'latex']
>>> choices("sweep")
['zarr', 'csv', 'json']
"""

from __future__ import annotations

import importlib
import pkgutil

from perturb.report.formats.base import Format, Reproduced

__all__ = ["FORMATS", "Format", "Reproduced", "choices", "keeps_warnings", "write"]


def _found() -> dict[str, Format]:
    out = {}
    for module in pkgutil.iter_modules(__path__):
        if module.name.endswith("_format"):
            entry = importlib.import_module(f"{__name__}.{module.name}").FORMAT
            out[entry.name] = entry
    return dict(sorted(out.items(), key=lambda item: (item[1].rank, item[0])))


#: Every format by name, in the order of the choice lists.
FORMATS: dict[str, Format] = _found()


def choices(kind: str) -> list[str]:
    """The formats that take results of ``kind``, in their order (``--format``'s choices).

    Parameters
    ----------
    kind : str
        A kind of result (see the module notes).

    Returns
    -------
    list of str

    Examples
    --------
    >>> from perturb.report.formats import choices
    >>> choices("solution"), choices("phase")
    (['table', 'csv', 'json', 'latex'], ['table', 'json'])
    """
    return [name for name, entry in FORMATS.items() if kind in entry.writers]


def write(kind: str, name: str, result) -> str:
    """``result`` (of ``kind``) written in the format ``name``: the exact text printed (empty
    for a ``failure`` the format does not write).

    Parameters
    ----------
    kind : str
        The kind of ``result`` (see the module notes).
    name : str
        The format, one of :func:`choices` of ``kind``.
    result : object

    Returns
    -------
    str
        The text, its trailing newline included (print it with ``end=""``).

    Examples
    --------
    >>> from perturb.report.formats import write
    >>> write("failure", "json", {"status": "failed"}), write("failure", "table", {})
    ('{"status": "failed"}\\n', '')
    """
    writers = FORMATS[name].writers
    if kind == "failure" and kind not in writers:
        return ""
    return writers[kind](result)


def keeps_warnings(name: str) -> bool:
    """Whether the format ``name`` carries a run's warnings in its document.

    Parameters
    ----------
    name : str

    Returns
    -------
    bool
        True when the document holds them (JSON's ``warnings``); else the CLI prints them to
        stderr.

    Examples
    --------
    >>> from perturb.report.formats import keeps_warnings
    >>> keeps_warnings("json"), keeps_warnings("table")
    (True, False)
    """
    return FORMATS[name].keeps_warnings
