"""The corpus of hostile calls of the public Python API (issue 10, item 3), run by test_api_fuzz.py.

Every case of :data:`CASES` is one call of a public constructor or method with a wrong type, a
non-finite number, an unknown key, a complex or non-analytic right-hand side, a mismatched length...
Each must end in one of two ways:

* **refused**: it raises a ``ValueError`` subclass of :mod:`perturb.errors` whose message is one line
  and names the argument in backticks (the case says which argument);
* **answered**: it returns, and the case's ``check`` accepts the result: a failed status with its
  reason, or a result that is correct (the pendulum-type ``eps*sin(x)`` is checked against the true
  period found by shooting).

Anything else counts against the API: another exception (``TypeError``, ``AttributeError``, a
sympy printer error), a message that does not name the argument, or a result the check rejects (a
``SUCCESS`` that silently dropped a term). ``python -m tests.engine.test_api_fuzz`` prints the
counts.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable

import numpy as np
import sympy as sp
from attrs import frozen

from perturb import (
    EPS,
    PeriodicSolution,
    PerturbError,
    PoincareMethod,
    QuasilinearSystem,
    solve,
)
from perturb.oracle import Scipy, find_periodic_orbit

X, XD, K = sp.symbols("x xdot k")
NAN, INF = float("nan"), float("inf")

#: Order-2 truncation error of a frequency whose coefficients are O(1): |Omega - Omega_2| <= C eps^3.
#: C = 1 leaves a factor ~10 over the eps^3 coefficient of the eps*sin(x) pendulum at A = 1 (~0.1).
TRUNCATION_C = 1.0
#: Shooting residual tolerance of the reference period (far below the truncation error tested).
REFERENCE_TOL = 1e-11


def duffing(**kw) -> QuasilinearSystem:
    args = {"coordinates": [X], "velocities": [XD], "frequencies": [1], "rhs": [-EPS * X**3]}
    args.update(kw)
    return QuasilinearSystem(**args)


def with_k() -> QuasilinearSystem:
    return QuasilinearSystem([X], [XD], [1], [-EPS * K * X**3], parameters=[K])


def one_dof(f) -> QuasilinearSystem:
    return QuasilinearSystem([X], [XD], [1], [f])


def _solution() -> PeriodicSolution:
    return solve(duffing(), 2, amplitudes={"x": 1})


def _solution_k() -> PeriodicSolution:
    return solve(with_k(), 2, amplitudes={"x": 1})


# ------------------------------------------------------------------------------ checks of results
def is_system(value) -> None:
    assert isinstance(value, QuasilinearSystem)
    for w in value.frequencies:
        assert w.is_number is False or (w.is_extended_real and w.is_finite and w > 0)


def failed_with_reason(value) -> None:
    """A failed construction that says why (never a SUCCESS)."""
    assert isinstance(value, PeriodicSolution)
    assert not value.success, f"SUCCESS returned: {value.frequency_series()}"
    assert value.message.strip()


def honest_solution(value) -> None:
    """Either a failed status with its reason or a real, finite solution."""
    assert isinstance(value, PeriodicSolution)
    if not value.success:
        assert value.message.strip()
        return
    omega = value.frequency_series()
    assert not omega.has(sp.I, sp.nan, sp.oo, sp.zoo, -sp.oo)


def equals(reference: Callable[[], object]):
    """The result must be exactly that of the clean call (extra `values` keys change nothing)."""

    def check(value) -> None:
        assert np.array_equal(np.asarray(value), np.asarray(reference()))

    return check


def finite_array(value) -> None:
    assert np.all(np.isfinite(np.asarray(value, dtype=float)))


def true_period(rhs: Callable, amplitude: float) -> float:
    orbit = find_periodic_orbit(
        lambda y: np.array([y[1], rhs(y[0], y[1]) - y[0]]),
        [amplitude, 0.0],
        2 * np.pi,
        section_index=1,
        fixed_indices=0,
        tol=REFERENCE_TOL,
        integrator=Scipy(rtol=1e-13),
    )
    assert orbit.success, orbit.message
    return orbit.period


def matches_shooting(f: sp.Expr, amplitude: float, eps: float = 0.05, order: int = 2):
    """The solution must succeed and give the true period to C eps^(order+1)."""
    numeric = sp.lambdify((X, XD), f.subs(EPS, eps), "math")

    def check(value) -> None:
        assert isinstance(value, PeriodicSolution) and value.success, value.message
        period = float(value.period_at(eps))
        reference = true_period(numeric, amplitude)
        assert abs(period - reference) / reference <= TRUNCATION_C * eps ** (order + 1)

    return check


# ------------------------------------------------------------------------------ the corpus
@frozen
class Case:
    """One hostile call; ``argument`` must be named by a refusal; ``check`` accepts a result
    (``None``: only a refusal is acceptable)."""

    name: str
    call: Callable[[], object]
    argument: str
    check: Callable[[object], None] | None = None


def _c(name, call, argument, check=None) -> Case:
    return Case(name, call, argument, check)


JUNK = {
    "None": None,
    "nan": NAN,
    "inf": INF,
    "-inf": -INF,
    "sympy.nan": sp.nan,
    "sympy.oo": sp.oo,
    "sympy.zoo": sp.zoo,
    "complex": 1 + 2j,
    "sympy.I": sp.I,
    "dict": {"a": 1},
    "bad str": "x**",
    "object": object(),
}

CASES: list[Case] = []
# QuasilinearSystem: frequencies
for label, junk in JUNK.items():
    CASES.append(
        _c(f"system frequencies={label}", lambda j=junk: duffing(frequencies=[j]), "frequencies")
    )
CASES += [
    _c("system frequencies=0", lambda: duffing(frequencies=[0]), "frequencies"),
    _c("system frequencies=-1", lambda: duffing(frequencies=[-1]), "frequencies"),
    _c("system frequencies=True", lambda: duffing(frequencies=[True]), "frequencies"),
    _c("system frequencies=[]", lambda: duffing(frequencies=[]), "frequencies"),
    _c("system frequencies two", lambda: duffing(frequencies=[1, 2]), "frequencies"),
    _c("system frequencies=state", lambda: duffing(frequencies=[X]), "frequencies"),
    _c("system frequencies=1+0j", lambda: duffing(frequencies=[1 + 0j]), "frequencies", is_system),
]
# QuasilinearSystem: right-hand sides
for label, junk in JUNK.items():
    CASES.append(_c(f"system rhs={label}", lambda j=junk: duffing(rhs=[j]), "rhs"))
CASES += [
    _c("system rhs=eps*nan", lambda: duffing(rhs=[EPS * sp.nan]), "rhs"),
    _c("system rhs=eps*oo*x", lambda: duffing(rhs=[EPS * sp.oo * X]), "rhs"),
    _c("system rhs=eps*inf*x", lambda: duffing(rhs=[EPS * INF * X]), "rhs"),
    _c("system rhs=I*eps*x", lambda: duffing(rhs=[sp.I * EPS * X]), "rhs"),
    _c("system rhs=eps*(x**2+I)", lambda: duffing(rhs=[EPS * (X**2 + sp.I)]), "rhs"),
    _c("system rhs=1j*eps*x", lambda: duffing(rhs=[1j * EPS * X]), "rhs"),
    _c(
        "solve rhs=eps*sqrt(-1-x**2)",
        lambda: solve(duffing(rhs=[EPS * sp.sqrt(-1 - X**2)]), 2, amplitudes={"x": 1}),
        "rhs",
        failed_with_reason,
    ),
    _c("system rhs not vanishing", lambda: duffing(rhs=[1 + EPS * X]), "rhs"),
    _c("system rhs undeclared", lambda: duffing(rhs=[EPS * sp.Symbol("y")]), "rhs"),
    _c("system rhs two", lambda: duffing(rhs=[EPS, EPS]), "rhs"),
    _c("system rhs=[]", lambda: duffing(rhs=[]), "rhs"),
    _c("system rhs=[True]", lambda: duffing(rhs=[True]), "rhs"),
    _c("system rhs=exp(-1/eps)", lambda: duffing(rhs=[sp.exp(-1 / EPS) * X]), "rhs"),
]
# QuasilinearSystem: the other arguments
CASES += [
    _c("system coordinates=None", lambda: duffing(coordinates=None), "coordinates"),
    _c("system coordinates=1", lambda: duffing(coordinates=1), "coordinates"),
    _c("system coordinates=[]", lambda: duffing(coordinates=[]), "coordinates"),
    _c("system coordinates=[None]", lambda: duffing(coordinates=[None]), "coordinates"),
    _c("system coordinates=[1.5]", lambda: duffing(coordinates=[1.5]), "coordinates"),
    _c("system coordinates=[x+1]", lambda: duffing(coordinates=[X + 1]), "coordinates"),
    _c("system coordinates=dict", lambda: duffing(coordinates={"x": 1}), "coordinates"),
    _c("system coordinates=['']", lambda: duffing(coordinates=[""]), "coordinates"),
    _c("system coordinates=['a b']", lambda: duffing(coordinates=["a b"]), "coordinates"),
    _c("system velocities=None", lambda: duffing(velocities=None), "velocities"),
    _c("system velocities=[]", lambda: duffing(velocities=[]), "velocities"),
    _c("system velocities=[1]", lambda: duffing(velocities=[1]), "velocities"),
    _c("system velocities=coordinate", lambda: duffing(velocities=[X]), "velocities"),
    _c("system velocities two", lambda: duffing(velocities=["v", "w"]), "velocities"),
    _c("system parameter=None", lambda: duffing(parameter=None), "parameter"),
    _c("system parameter=1", lambda: duffing(parameter=1), "parameter"),
    _c("system parameter=2.5", lambda: duffing(parameter=2.5), "parameter"),
    _c("system parameter=[]", lambda: duffing(parameter=[]), "parameter"),
    _c("system parameter=x", lambda: duffing(parameter="x"), "parameter"),
    _c("system regime=medium", lambda: duffing(regime="medium"), "regime"),
    _c("system regime=None", lambda: duffing(regime=None), "regime"),
    _c("system regime=3", lambda: duffing(regime=3), "regime"),
    _c("system parameters=None", lambda: duffing(parameters=None), "parameters"),
    _c("system parameters=5", lambda: duffing(parameters=5), "parameters"),
    _c("system parameters=[1]", lambda: duffing(parameters=[1]), "parameters"),
    _c("system parameters=[None]", lambda: duffing(parameters=[None]), "parameters"),
    _c("system parameters=['x']", lambda: duffing(parameters=["x"]), "parameters"),
    _c("system initial_values short", lambda: duffing(initial_values=["a"]), "initial_values"),
    _c("system initial_values=[1,2]", lambda: duffing(initial_values=[1, 2]), "initial_values"),
    _c("system initial_values=None", lambda: duffing(initial_values=None), "initial_values"),
    _c("system first_integrals=[None]", lambda: duffing(first_integrals=[None]), "first_integrals"),
    _c("system first_integrals=bad", lambda: duffing(first_integrals=["x**"]), "first_integrals"),
    _c("system first_integrals=[nan]", lambda: duffing(first_integrals=[NAN]), "first_integrals"),
    _c("system name=3", lambda: duffing(name=3), "name"),
    _c("system name=None", lambda: duffing(name=None), "name"),
    _c("system truncation=1", lambda: duffing(truncation=1), "truncation"),
    _c("system truncation=2.5", lambda: duffing(truncation=2.5), "truncation"),
    _c("system truncation='3'", lambda: duffing(truncation="3"), "truncation"),
    _c("system truncation=True", lambda: duffing(truncation=True), "truncation"),
    _c("system truncation=nan", lambda: duffing(truncation=NAN), "truncation"),
    _c("system unknown keyword", lambda: duffing(damping=1), "damping"),
]
# QuasilinearSystem methods
CASES += [
    _c("with_values unknown key", lambda: with_k().with_values({"zz": 1}), "values"),
    _c("with_values nan", lambda: with_k().with_values({"k": NAN}), "values"),
    _c("with_values oo", lambda: with_k().with_values({"k": sp.oo}), "values"),
    _c("with_values complex", lambda: with_k().with_values({"k": 1j}), "values"),
    _c("with_values bad str", lambda: with_k().with_values({"k": "x**"}), "values"),
    _c("with_values None", lambda: with_k().with_values({"k": None}), "values"),
    _c("with_values list", lambda: with_k().with_values([1]), "values"),
    _c("with_values str", lambda: with_k().with_values("k"), "values"),
    _c("vector_field nan", lambda: with_k().vector_field(NAN, {"k": 1}), "epsilon"),
    _c("vector_field str", lambda: with_k().vector_field("a", {"k": 1}), "epsilon"),
    _c("vector_field unknown key", lambda: with_k().vector_field(0.1, {"k": 1, "q": 2}), "values"),
    _c("vector_field nan value", lambda: with_k().vector_field(0.1, {"k": NAN}), "values"),
    _c("vector_field values list", lambda: with_k().vector_field(0.1, [1]), "values"),
    _c("as_large_parameter=5", lambda: duffing().as_large_parameter(5), "mu"),
    _c("as_large_parameter=x", lambda: duffing().as_large_parameter("x"), "mu"),
    _c("expansion order=-1", lambda: duffing().expansion(-1), "order"),
    _c("expansion order='2'", lambda: duffing().expansion("2"), "order"),
]
# PoincareMethod / solve options
_S = duffing
CASES += [
    _c("order=0", lambda: PoincareMethod(order=0), "order"),
    _c("order=-1", lambda: PoincareMethod(order=-1), "order"),
    _c("order=1.5", lambda: PoincareMethod(order=1.5), "order"),
    _c("order='2'", lambda: PoincareMethod(order="2"), "order"),
    _c("order=None", lambda: PoincareMethod(order=None), "order"),
    _c("order=True", lambda: PoincareMethod(order=True), "order"),
    _c("order=nan", lambda: PoincareMethod(order=NAN), "order"),
    _c("order=10**6", lambda: PoincareMethod(order=10**6), "order"),
    _c("amplitudes unknown key", lambda: solve(_S(), amplitudes={"y": 1}), "amplitudes"),
    _c("amplitudes nan", lambda: solve(_S(), amplitudes={"x": NAN}), "amplitudes"),
    _c("amplitudes inf", lambda: solve(_S(), amplitudes={"x": INF}), "amplitudes"),
    _c("amplitudes oo", lambda: solve(_S(), amplitudes={"x": sp.oo}), "amplitudes"),
    _c("amplitudes zoo", lambda: solve(_S(), amplitudes={"x": sp.zoo}), "amplitudes"),
    _c("amplitudes complex", lambda: solve(_S(), amplitudes={"x": 1j}), "amplitudes"),
    _c("amplitudes I", lambda: solve(_S(), amplitudes={"x": sp.I}), "amplitudes"),
    _c("amplitudes bad str", lambda: solve(_S(), amplitudes={"x": "x**"}), "amplitudes"),
    _c("amplitudes None value", lambda: solve(_S(), amplitudes={"x": None}), "amplitudes"),
    _c("amplitudes=list", lambda: solve(_S(), amplitudes=[1]), "amplitudes"),
    _c("amplitudes=str", lambda: solve(_S(), amplitudes="x"), "amplitudes"),
    _c("amplitudes=5", lambda: solve(_S(), amplitudes=5), "amplitudes"),
    _c("amplitudes int key", lambda: solve(_S(), amplitudes={1: 2}), "amplitudes"),
    _c(
        "amplitudes symbol key",
        lambda: solve(_S(), amplitudes={X: 1}),
        "amplitudes",
        honest_solution,
    ),
    _c("amplitudes=-1", lambda: solve(_S(), amplitudes={"x": -1}), "amplitudes", honest_solution),
    _c("phase_coordinate=y", lambda: solve(_S(), phase_coordinate="y"), "phase_coordinate"),
    _c("phase_coordinate=1", lambda: PoincareMethod(phase_coordinate=1), "phase_coordinate"),
    _c("phase_coordinate=symbol", lambda: PoincareMethod(phase_coordinate=X), "phase_coordinate"),
    _c("branch unknown key", lambda: solve(_S(), branch={"zzz": 1}), "branch"),
    _c("branch=str", lambda: solve(_S(), branch="abc"), "branch"),
    _c("branch=1.5", lambda: solve(_S(), branch=1.5), "branch"),
    _c("branch=True", lambda: solve(_S(), branch=True), "branch"),
    _c("branch=[1]", lambda: solve(_S(), branch=[1]), "branch"),
    _c("branch nan value", lambda: solve(_S(), branch={"a_x0": NAN}), "branch"),
    _c("branch=99", lambda: solve(_S(), branch=99), "branch", honest_solution),
    _c("quadrature=fast", lambda: PoincareMethod(quadrature="fast"), "quadrature"),
    _c("quadrature=None", lambda: PoincareMethod(quadrature=None), "quadrature"),
    _c("quadrature=1", lambda: PoincareMethod(quadrature=1), "quadrature"),
    _c(
        "dependent_condition=x",
        lambda: PoincareMethod(dependent_condition="x"),
        "dependent_condition",
    ),
    _c(
        "dependent_condition=None",
        lambda: PoincareMethod(dependent_condition=None),
        "dependent_condition",
    ),
    _c("solve_seconds=-1", lambda: PoincareMethod(solve_seconds=-1), "solve_seconds"),
    _c("solve_seconds=0", lambda: PoincareMethod(solve_seconds=0), "solve_seconds"),
    _c("solve_seconds=nan", lambda: PoincareMethod(solve_seconds=NAN), "solve_seconds"),
    _c("solve_seconds='1'", lambda: PoincareMethod(solve_seconds="1"), "solve_seconds"),
    _c("solve_seconds=None", lambda: PoincareMethod(solve_seconds=None), "solve_seconds"),
    _c("cache='yes'", lambda: PoincareMethod(cache="yes"), "cache"),
    _c("unknown option", lambda: PoincareMethod(ordr=2), "ordr"),
    _c("solve unknown option", lambda: solve(_S(), 1, foo=1), "foo"),
    _c("solve system=None", lambda: solve(None), "system"),
    _c("solve system=str", lambda: solve("duffing"), "system"),
    _c("method.solve system=5", lambda: PoincareMethod().solve(5), "system"),
    _c("solve order='1'", lambda: solve(_S(), "1"), "order"),
]
# Right-hand sides not polynomial in the state
_A1 = {"x": 1}
CASES += [
    _c(
        "rhs eps*sqrt(x) A=1",
        lambda: solve(one_dof(EPS * sp.sqrt(X)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c("rhs eps*sqrt(x)", lambda: solve(one_dof(EPS * sp.sqrt(X)), 2), "rhs", failed_with_reason),
    _c(
        "rhs eps*abs(x) A=1",
        lambda: solve(one_dof(EPS * sp.Abs(X)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*sign(xdot) A=1",
        lambda: solve(one_dof(EPS * sp.sign(XD)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*x**(1/3) A=1",
        lambda: solve(one_dof(EPS * X ** sp.Rational(1, 3)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps/x A=1",
        lambda: solve(one_dof(EPS / X), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*log(x) A=1",
        lambda: solve(one_dof(EPS * sp.log(X)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*Heaviside(x) A=1",
        lambda: solve(one_dof(EPS * sp.Heaviside(X)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*Max(x,0) A=1",
        lambda: solve(one_dof(EPS * sp.Max(X, 0)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps/(1+x) A=1",
        lambda: solve(one_dof(EPS / (1 + X)), 2, amplitudes=_A1),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*tan(x) A=2",
        lambda: solve(one_dof(EPS * sp.tan(X)), 2, amplitudes={"x": 2}),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*sin(x) A=1",
        lambda: solve(one_dof(EPS * sp.sin(X)), 2, amplitudes=_A1),
        "rhs",
        matches_shooting(EPS * sp.sin(X), 1.0),
    ),
    _c("rhs eps*sin(x)", lambda: solve(one_dof(EPS * sp.sin(X)), 2), "rhs", failed_with_reason),
    _c(
        "rhs eps*sqrt(2+x) A=1",
        lambda: solve(one_dof(EPS * sp.sqrt(2 + X)), 2, amplitudes=_A1),
        "rhs",
        matches_shooting(EPS * sp.sqrt(2 + X), 1.0),
    ),
    _c(
        "rhs eps/(2+x) A=1",
        lambda: solve(one_dof(EPS / (2 + X)), 2, amplitudes=_A1),
        "rhs",
        matches_shooting(EPS / (2 + X), 1.0),
    ),
    _c(
        "rhs eps*(exp(x)-1) A=1",
        lambda: solve(one_dof(EPS * (sp.exp(X) - 1)), 2, amplitudes=_A1),
        "rhs",
        matches_shooting(EPS * (sp.exp(X) - 1), 1.0),
    ),
    _c(
        "rhs eps*sqrt(x) numeric",
        lambda: solve(one_dof(EPS * sp.sqrt(X)), 2, amplitudes=_A1, quadrature="numeric"),
        "rhs",
        failed_with_reason,
    ),
    _c(
        "rhs eps*sqrt(x) exact",
        lambda: solve(one_dof(EPS * sp.sqrt(X)), 2, amplitudes=_A1, quadrature="exact"),
        "rhs",
        failed_with_reason,
    ),
]
# PeriodicSolution methods
CASES += [
    _c("evaluate t=nan", lambda: _solution().evaluate(NAN, 0.1), "t"),
    _c("evaluate t=[0,nan]", lambda: _solution().evaluate([0, NAN], 0.1), "t"),
    _c("evaluate t=inf", lambda: _solution().evaluate(INF, 0.1), "t"),
    _c("evaluate t=1j", lambda: _solution().evaluate(1j, 0.1), "t"),
    _c("evaluate t=str", lambda: _solution().evaluate("abc", 0.1), "t"),
    _c("evaluate t=None", lambda: _solution().evaluate(None, 0.1), "t"),
    _c("evaluate t=dict", lambda: _solution().evaluate({}, 0.1), "t"),
    _c("evaluate t ragged", lambda: _solution().evaluate([[0, 1], [2]], 0.1), "t"),
    _c("evaluate eps=nan", lambda: _solution().evaluate(0.0, NAN), "epsilon"),
    _c("evaluate eps=1j", lambda: _solution().evaluate(0.0, 1j), "epsilon"),
    _c("evaluate eps=str", lambda: _solution().evaluate(0.0, "a"), "epsilon"),
    _c("evaluate eps=None", lambda: _solution().evaluate(0.0, None), "epsilon"),
    _c(
        "evaluate values unknown key",
        lambda: _solution().evaluate(0.0, 0.1, {"zz": 1}),
        "values",
        equals(lambda: _solution().evaluate(0.0, 0.1)),
    ),
    _c("evaluate values int key", lambda: _solution_k().evaluate(0.0, 0.1, {1: 1}), "values"),
    _c("evaluate values=list", lambda: _solution().evaluate(0.0, 0.1, [1]), "values"),
    _c("evaluate values k=nan", lambda: _solution_k().evaluate(0.0, 0.1, {"k": NAN}), "values"),
    _c("evaluate values k=str", lambda: _solution_k().evaluate(0.0, 0.1, {"k": "a"}), "values"),
    _c("evaluate values k=1j", lambda: _solution_k().evaluate(0.0, 0.1, {"k": 1j}), "values"),
    _c(
        "evaluate values extra key",
        lambda: _solution_k().evaluate(0.0, 0.1, {"k": 1, "q": 2}),
        "values",
        equals(lambda: _solution_k().evaluate(0.0, 0.1, {"k": 1})),
    ),
    _c("evaluate values=None k missing", lambda: _solution_k().evaluate(0.0, 0.1), "values"),
    _c("evaluate 2-D t", lambda: _solution().evaluate([[0.0, 1.0]], 0.1), "t", finite_array),
    _c("period_at nan", lambda: _solution().period_at(NAN), "epsilon"),
    _c("period_at str", lambda: _solution().period_at("x"), "epsilon"),
    _c("period_at None", lambda: _solution().period_at(None), "epsilon"),
    _c("period_at 1j", lambda: _solution().period_at(1j), "epsilon"),
    _c(
        "period_at values unknown",
        lambda: _solution().period_at(0.1, {"zz": 1}),
        "values",
        equals(lambda: _solution().period_at(0.1)),
    ),
    _c("initial_state inf", lambda: _solution().initial_state(INF), "epsilon"),
    _c(
        "initial_state values unknown",
        lambda: _solution().initial_state(0.1, {"zz": 1}),
        "values",
        equals(lambda: _solution().initial_state(0.1)),
    ),
    _c("coefficients nan", lambda: _solution().coefficients(NAN), "epsilon"),
    _c("coordinate y", lambda: _solution().coordinate("y"), "name"),
    _c("coordinate 1", lambda: _solution().coordinate(1), "name"),
    _c("coordinate None", lambda: _solution().coordinate(None), "name"),
    _c("coordinate symbol", lambda: _solution().coordinate(X), "name", lambda v: None),
]


# ------------------------------------------------------------------------------ classification
def outcome(case: Case) -> tuple[str, str]:
    """``("refused" | "answered" | "other exception" | "bad message" | "not refused"
    | "wrong result", detail)``."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            value = case.call()
    except Exception as exc:  # noqa: BLE001 (classifying every exception is the point)
        message = str(exc)
        if not (isinstance(exc, PerturbError) and isinstance(exc, ValueError)):
            return "other exception", f"{type(exc).__name__}: {message[:200]}"
        if "\n" in message.strip() or f"`{case.argument}" not in message:
            return "bad message", message[:300]
        return "refused", message
    if case.check is None:
        return "not refused", repr(value)[:200]
    try:
        case.check(value)
    except AssertionError as exc:
        return "wrong result", str(exc)[:300]
    return "answered", ""
