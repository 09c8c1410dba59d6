"""Every branch of a driven model's response at its own point: :func:`steady_state_of`."""

from __future__ import annotations

__all__ = ["steady_state_of"]


def steady_state_of(model, order: int = 1):
    """Every branch of a driven ``model``'s steady-state response at its parameter values
    (:func:`perturb.steady.steady_state` at the model's symbols and ε), kept per system, order
    and point: what ``perturb families`` lists for a driven problem.

    Parameters
    ----------
    model : Model
        A driven problem at a point (``problems.Problem``), or any
        :class:`~perturb.validation.Model` of a driven system.
    order : int, optional
        The order of the series (0: the first-order amplitude equations alone).

    Returns
    -------
    perturb.steady.SteadyState
        Its ``points`` (amplitudes, stability), their ``names`` (stable across orders).

    Examples
    --------
    >>> from perturb.response import steady_state_of
    >>> from problems import get_problem
    >>> state = steady_state_of(get_problem("forced-duffing").create(Omega=1.2), 1)
    >>> len(state.points), [p.stable for p in state.points]
    (3, [True, False, True])
    """
    from perturb.validation.frames import steady_states

    return steady_states(model.system(), order, model.symbol_values(), model.epsilon())
