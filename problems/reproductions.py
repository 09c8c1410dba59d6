"""Registry of paper reproductions: what ``perturb reproduce NAME`` can run.

A reproduction is a subclass of :class:`Reproduction` decorated with
``@register_reproduction("name")``.  The CLI looks names up here (:func:`get_reproduction`) and
never imports a reproduction's module itself.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
from importlib import import_module
from typing import Any, ClassVar

from perturb.errors import UnknownNameError

__all__ = [
    "Reproduction",
    "get_reproduction",
    "register_reproduction",
    "reproduction_names",
]

#: Modules whose import registers reproductions; imported on the first lookup only, so that
#: importing :mod:`problems` stays cheap.
_PROVIDERS = ("problems.rigid_body.paper",)

_REGISTRY: dict[str, type[Reproduction]] = {}


class Reproduction(ABC):
    """A published paper's reproduction, as ``perturb reproduce NAME`` runs it.

    Contract for implementers:

    1. Decorate the subclass with ``@register_reproduction(name)``; this sets :attr:`name`.
    2. :meth:`run` computes everything and returns a report (a value object holding data only).
       When ``output`` is given it checks that directory *before* any work (raising
       :class:`~perturb.errors.InvalidParameterError` naming ``--output``) and writes the report
       files into it.
    3. :meth:`as_dict` turns the report into a JSON-serialisable dict; its keys are a contract for
       users' scripts (``--format json``).
    4. :meth:`summary` returns the one-screen text printed by default: the verdict and the
       headline figures, at most about 30 lines.
    5. :meth:`full` returns the full tables (``--full``).
    """

    name: ClassVar[str] = ""

    @abstractmethod
    def run(self, output=None) -> Any:
        """Reproduce the paper; write the report files into the directory ``output`` if given."""

    @abstractmethod
    def as_dict(self, report: Any) -> dict:
        """The report as a JSON-serialisable dict."""

    @abstractmethod
    def summary(self, report: Any) -> str:
        """The one-screen summary."""

    @abstractmethod
    def full(self, report: Any) -> str:
        """The full tables as text."""


def register_reproduction(
    name: str,
) -> Callable[[type[Reproduction]], type[Reproduction]]:
    """Class decorator adding a :class:`Reproduction` subclass to the registry under ``name``.

    Raises
    ------
    TypeError
        If the decorated class is not a :class:`Reproduction` subclass.
    """

    def decorate(cls: type[Reproduction]) -> type[Reproduction]:
        if not (isinstance(cls, type) and issubclass(cls, Reproduction)):
            raise TypeError(f"@register_reproduction({name!r}) needs a Reproduction subclass")
        cls.name = name
        _REGISTRY[name] = cls
        return cls

    return decorate


def _load_providers() -> None:
    for module in _PROVIDERS:
        import_module(module)


def reproduction_names() -> list[str]:
    """The names ``perturb reproduce`` accepts, sorted."""
    _load_providers()
    return sorted(_REGISTRY)


def get_reproduction(name: str) -> Reproduction:
    """The reproduction registered as ``name`` (an instance, ready to :meth:`~Reproduction.run`).

    Raises
    ------
    perturb.errors.UnknownNameError
        If ``name`` is not registered (the message lists the known names).
    """
    _load_providers()
    if name not in _REGISTRY:
        raise UnknownNameError(f"`paper` = {name!r} is unknown: choose from {reproduction_names()}")
    return _REGISTRY[name]()
