"""The one default order of every command: ``--order`` when given, else the problem's kind's.

A driven problem's default is :data:`~perturb._defaults.DRIVEN_ORDER` (its response is continued,
so order 3 costs about what order 1 does; the amplitude equations of every shipped driven problem
at order 3 take 0.2 to 3 s to derive), a free problem's :data:`~perturb._defaults.FREE_ORDER` (a
rigid body's derivation grows steeply with the order). So ``perturb validate`` checks the series
``perturb response`` drew, ``perturb families`` lists the branches ``perturb phase-diagram``
counts, and every header prints the order it used.
"""

from __future__ import annotations

from perturb.cli._values import _parse_order


def default_order(problem) -> int:
    """The order a command uses for ``problem`` when ``--order`` is not given (the frame's:
    :attr:`perturb.validation.frames.FrameWork.default_order`)."""
    from perturb.validation.frames import work_of

    return work_of(problem.system()).default_order


def order_of(text: str | None, problem) -> int:
    """``--order``'s value (checked: exit 2 on a bad one), or :func:`default_order`."""
    return default_order(problem) if text is None else _parse_order(text)
