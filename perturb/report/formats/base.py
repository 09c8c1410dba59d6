"""The entry of a format (:class:`Format`) and the small holders some writers take."""

from __future__ import annotations

from collections.abc import Callable, Mapping

from attrs import field, frozen

__all__ = ["Format", "Reproduced"]


@frozen
class Format:
    """One output format.

    Parameters
    ----------
    name : str
        ``--format NAME``.
    writers : mapping of str to callable
        ``{kind of result: writer}``; a writer takes the result and returns the exact text printed
        (its trailing newline included).
    rank : int
        Its place in a choice list (``table`` first).
    keeps_warnings : bool
        Whether its document carries a run's warnings itself (JSON's ``warnings``); otherwise the
        CLI prints them to stderr.

    Examples
    --------
    A format that writes validation reports as one line (a module ``one_line_format.py`` in
    this package holding it as ``FORMAT`` is all it takes to offer ``--format one-line``):

    >>> from perturb.report.formats import Format
    >>> one_line = Format("one-line", {"validation": lambda report: f"{report.outcome.name}\\n"})
    >>> sorted(one_line.writers), one_line.keeps_warnings
    (['validation'], False)
    """

    name: str
    writers: Mapping[str, Callable[[object], str]] = field(converter=dict)
    rank: int = 100
    keeps_warnings: bool = False


@frozen
class Reproduced:
    """A reproduction's report with what writes it (``perturb reproduce``).

    Attributes
    ----------
    reproduction : object
        The registered reproduction (``summary``, ``full``, ``as_dict``).
    report : object
    full : bool
        Whether the table adds the full report after the summary.

    Examples
    --------
    >>> from perturb.report.formats import Reproduced, write
    >>> class Paper:
    ...     def summary(self, report): return f"{report} reproduced"
    ...     def full(self, report): return "every table"
    ...     def as_dict(self, report): return {"report": report}
    >>> print(write("reproduction", "table", Reproduced(Paper(), "paper", full=True)), end="")
    paper reproduced
    <BLANKLINE>
    every table
    >>> write("reproduction", "json", Reproduced(Paper(), "paper"))
    '{"report": "paper"}\\n'
    """

    reproduction: object
    report: object
    full: bool = False
