"""The resonant chain's order-1 amplitude equations as the construction poses them: shared by
``tests/algebra/test_chain.py`` and ``benchmarks/bench_chain.py`` (and through it
``bench_chain_homotopy.py``), so that the tests and the benchmarks solve the very same systems."""

from __future__ import annotations

import sympy as sp

from perturb import solve
from perturb.method import conditions
from problems.resonant_chain import chain_system


def amplitude_equations(n: int):
    """The order-1 amplitude equations of the chain of ``n`` (x1's amplitude 1) and their unknowns,
    caught where the engine hands them to its solver (the common factor pi divided out)."""
    captured = {}
    original = conditions.ConditionSolver._solve_nonlinear

    def capture(self, eqs, unknowns, *args):
        captured.update(eqs=[sp.expand(e / sp.pi) for e in eqs], unknowns=list(unknowns))
        raise KeyboardInterrupt  # stop the construction here

    conditions.ConditionSolver._solve_nonlinear = capture
    try:
        solve(chain_system(n), order=1, amplitudes={"x1": 1}, cache=False)
    except KeyboardInterrupt:
        pass
    finally:
        conditions.ConditionSolver._solve_nonlinear = original
    return captured["eqs"], captured["unknowns"]


def pairs_of(n: int):
    """Each coordinate's (cosine, sine) generating amplitudes (x1's put in: 1 and 0)."""
    return [(sp.Integer(1), sp.Integer(0))] + [
        (sp.Symbol(f"a_x{j}0"), sp.Symbol(f"b_x{j}0")) for j in range(2, n + 1)
    ]
