"""The steady-state branches of a driven system at one parameter point, and their solutions.

:func:`branches_at` finds every order-N branch at the given values: the certified first-order
census at the point (exact rationals, :func:`~perturb.steady.roots.real_roots`) seeds the
continuation of each branch in the detuning around it (:mod:`perturb.steady.traced`), carried
to order N; stability from the Floquet multipliers along each order-N orbit
(:mod:`perturb.steady.floquet`);
:func:`branch_solution` is the :class:`~perturb.PeriodicSolution` of one branch (its amplitudes put
in), which evaluates, validates and exports like any other; :func:`branch_names` names them.
"""

from __future__ import annotations

import cmath
import math
import re
from collections.abc import Mapping

import attrs
import sympy as sp

from perturb._defaults import SINGLE_POINT_SHARE, SINGLE_POINT_WINDOW
from perturb.errors import InvalidParameterError, bad_value
from perturb.method.driven import AmplitudeEquations
from perturb.method.family_names import response_shape
from perturb.solution import PeriodicSolution, Status
from perturb.steady.exact import exact_number
from perturb.steady.point import BranchPoint

__all__ = [
    "BranchPoint",
    "SteadyState",
    "branch_names",
    "branch_solution",
    "branches_at",
    "exact_number",
    "steady_state",
]


def _fixed(equations: AmplitudeEquations, values: Mapping) -> dict:
    names = {p.name: p for p in equations.system.parameters}
    missing = sorted(set(names) - set(values))
    if missing:
        raise bad_value("values", dict(values), f"give values for {missing}", InvalidParameterError)
    return {names[k]: exact_number(values[k]) for k in names}


def branches_at(
    equations: AmplitudeEquations, values: Mapping, epsilon: float, order: int = 1
) -> tuple[list[BranchPoint], str]:
    """Every order-N steady-state response at these parameter values.

    The first-order equations are solved for every real root at the point (certified); each
    first-order branch through it is followed in the detuning σ over a window around the point,
    carried to order N by the homotopy in the truncation and continued at order N through its
    folds (:func:`perturb.steady.traced.trace`); the order-N curves are read at the point. A
    first-order root with no order-N branch over it gives none, and an order-N branch whose
    first-order counterpart turned before the point is found (softening beyond the first-order
    fold). Stability from the Floquet multipliers along each order-N orbit.

    Returns
    -------
    (list of BranchPoint, str)
        The branches sorted by amplitude (max ``|x|``), and "" or why the roots could not be
        enumerated (then the list is empty: never a silent drop).
    """
    points, why, _ = _branches(equations, values, epsilon, order)
    return points, why


def _branches(equations: AmplitudeEquations, values: Mapping, epsilon: float, order: int):
    """:func:`branches_at` with each branch's order-(N−1) root reached from it (None: none was,
    or order 0), in the branches' order: ``(points, why, lowers)``."""
    from perturb.steady.evaluate import PointEvaluator
    from perturb.steady.line import excitation_frequency, line_of_values
    from perturb.steady.traced import trace

    fixed = _fixed(equations, values)
    floats = {k.name: float(v) for k, v in fixed.items()}
    excitation_frequency(equations.system, floats, float(epsilon))
    names = [p.name for p in equations.system.parameters]
    detuning = equations.system.excitation.detuning
    swept = detuning.name if isinstance(detuning, sp.Symbol) and detuning.name in floats else None
    if swept is None:  # no detuning to follow: the point's roots carried by the homotopy alone
        swept = names[0] if names else None
    if swept is None:
        return [], "the system has no parameter to continue its branches in", []
    line = line_of_values(names, floats, float(epsilon), swept)
    centre = floats[swept]
    half = max(SINGLE_POINT_WINDOW, SINGLE_POINT_SHARE * abs(centre))
    traced = trace(equations, order, line, centre - half, centre + half, census_at=[centre],
                   folds=False)  # fmt: skip
    census_failed = [f for f in traced.failures if f.startswith(f"{swept} = ")]
    if census_failed:
        return [], census_failed[0].split(": ", 1)[1], []
    found = traced.at([centre])[0]
    if not found:
        return [], "", []
    evaluator = PointEvaluator(equations, line)
    at = evaluator.evaluate([u for u, _ in found], [centre] * len(found))
    trouble = "; ".join(traced.failures)
    out = []
    amplitude_names = [s.name for s in equations.amplitudes]
    for k, (u, _) in enumerate(found):
        stability = at["stability"]
        multipliers = tuple(complex(z) for z in stability.multipliers[k])
        reasons = at["reasons"][k]
        note = "; ".join(
            filter(None, [
                "the series is outside its domain here: " + "; ".join(reasons) if reasons else "",
                f"a continuation in the window around the point failed: {trouble}" if trouble else "",
            ])
        )  # fmt: skip
        out.append(
            BranchPoint(
                amplitudes=dict(zip(amplitude_names, map(float, u), strict=True)),
                norms={c: float(v[k]) for c, v in at["initial"].items()},
                stable=stability.stable[k],
                eigenvalues=tuple(
                    cmath.log(z) / float(epsilon) if z else complex(-math.inf) for z in multipliers
                ),  # fmt: skip
                multipliers=multipliers,
                note=note,
                peak={c: float(v[k]) for c, v in at["peak"].items()},
                first_harmonic={c: float(v[k]) for c, v in at["first-harmonic"].items()},
                error=at["error"][k],
                series_ok=not reasons,
                liouville=float(stability.liouville[k]),
            )
        )
    ranked = sorted(range(len(out)), key=lambda k: (*out[k].peak.values(), *out[k].norms.values()))
    return [out[k] for k in ranked], "", [at["lower"][k] for k in ranked]


def count_name(name: str) -> bool:
    """Whether ``name`` is one of the names :func:`branch_names` gives by count (or by mode shape
    and count)."""
    if name in ("trivial", "response", "lower", "middle", "upper"):
        return True
    if _SHAPE_NAME.fullmatch(name):
        return True
    head, _, tail = name.rpartition("-")
    return head in ("branch", "beyond-series") and tail.isdigit()


#: A many-mode branch's name: its mode shape (:func:`perturb.method.family_names.response_shape`)
#: and its rank among the branches of that shape.
_SHAPE_NAME = re.compile(
    r"(in-phase|anti-phase|shape-[pn0]+)(-localised-[^\s]+?)?(-(lower|middle|upper|\d+))?"
)


def branch_names(points: list[BranchPoint], harmonics: tuple | None = None) -> list[str]:
    """Stable names for the branches at one point, sorted by amplitude: ``trivial`` (x = 0), then
    ``response`` (one), ``lower``/``upper`` (two), ``lower``/``middle``/``upper`` (three),
    else ``branch-1``, ``branch-2``, …; a root where the series is outside its domain
    (``series_ok`` False: no lower-order counterpart, terms not decreasing) is ``beyond-series-1``,
    … and not counted, so that it never renames the others.

    With several resonant coordinates a branch is named by its mode shape first
    (:func:`perturb.method.family_names.response_shape`: ``in-phase``, ``anti-phase``,
    ``shape-pnn``, with ``-localised-x1``), and the branches of one shape by amplitude as above:
    ``in-phase`` alone, ``in-phase-lower`` and ``in-phase-upper``, ``in-phase-1``, … — when the
    coordinates resonate at one harmonic (``harmonics``, the m_i of
    :class:`~perturb.method.driven.AmplitudeEquations`, all equal, or not given): phases of
    different harmonics are not comparable, so a 1:2 absorber's branches keep their amplitude
    names (``lower``, ``upper``)."""
    trivial = [p for p in points if p.trivial]
    beyond = [p for p in points if not p.trivial and not getattr(p, "series_ok", True)]
    others = [p for p in points if not p.trivial and getattr(p, "series_ok", True)]
    labels = {1: ["response"], 2: ["lower", "upper"], 3: ["lower", "middle", "upper"]}
    one_harmonic = harmonics is None or len(set(harmonics)) <= 1
    if others and len(others[0].norms) > 1 and one_harmonic:
        out = {}
        groups: dict[str, list] = {}
        for p in others:
            groups.setdefault(response_shape(_complex(p)), []).append(p)
        for shape, members in groups.items():
            ranks = labels.get(len(members), [str(k + 1) for k in range(len(members))])
            for p, rank in zip(members, ranks, strict=True):
                out[id(p)] = shape if rank == "response" else f"{shape}-{rank}"
    else:
        names = labels.get(len(others), [f"branch-{k + 1}" for k in range(len(others))])
        out = {id(p): n for p, n in zip(others, names, strict=True)}
    out.update({id(p): f"beyond-series-{k + 1}" for k, p in enumerate(beyond)})
    out.update({id(p): "trivial" for p in trivial})
    return [out[id(p)] for p in points]


def _complex(point) -> dict:
    """``{coordinate: a - ib}`` of a response point (its resonant harmonic's amplitudes)."""
    return {
        c: complex(point.amplitudes[f"a_{c}"], -point.amplitudes[f"b_{c}"]) for c in point.norms
    }


def branch_solution(
    equations: AmplitudeEquations, point: BranchPoint, name: str = ""
) -> PeriodicSolution:
    """The periodic solution of one branch: the series with its amplitudes put in.

    The solution's system is the driven system itself (its parameters stay symbols, evaluated
    with the problem's values); the amplitudes are numbers (30 significant digits of the
    double-precision root). ``message`` says which branch it is and its stability.
    """
    series = equations.solution
    amplitude_symbols = set(equations.amplitudes)
    subs = {s: sp.Float(point.amplitudes[s.name], 30) for s in equations.amplitudes}
    terms = tuple(
        tuple(t.map(lambda c, s=subs: c.xreplace(s)) for t in row) for row in series.terms
    )
    generating = attrs.evolve(
        series.generating,
        cos_amplitudes=tuple(
            sp.sympify(a).xreplace(subs) for a in series.generating.cos_amplitudes
        ),
        sin_amplitudes=tuple(
            sp.sympify(b).xreplace(subs) for b in series.generating.sin_amplitudes
        ),
    )
    system = attrs.evolve(
        series.system,
        parameters=tuple(p for p in series.system.parameters if p not in amplitude_symbols),
    )
    deviations = {
        k: tuple(sp.sympify(v).xreplace(subs) for v in vs) for k, vs in series.deviations.items()
    }
    stability = {True: "stable", False: "unstable", None: "on a fold (marginal)"}[point.stable]
    message = (
        f"branch {name or 'of the response'}: amplitudes "
        + ", ".join(f"{k} = {v:.6g}" for k, v in point.amplitudes.items())
        + f"; {stability} (Floquet)"
        + (f"; {point.note}" if point.note else "")
    )
    return attrs.evolve(
        series,
        system=system,
        terms=terms,
        generating=generating,
        deviations=deviations,
        status=Status.SUCCESS,
        message=message,
    )


@attrs.frozen
class SteadyState:
    """Every branch of a driven system's response at one parameter point.

    Attributes
    ----------
    points : tuple of BranchPoint
        Sorted by amplitude.
    names : tuple of str
        :func:`branch_names` of ``points``.
    equations : AmplitudeEquations
    why : str
        Empty, or why the roots could not be enumerated (then ``points`` is empty).
    """

    points: tuple = attrs.field(converter=tuple)
    names: tuple = attrs.field(converter=tuple)
    equations: AmplitudeEquations = attrs.field(eq=False)
    why: str = ""

    def solution(self, name: str | None = None) -> PeriodicSolution:
        """The branch ``name`` (default: the largest non-trivial amplitude) as a solution; a
        failed one (``NO_ROOT`` with the reason) when there is none."""
        from perturb.errors import UnknownNameError

        if self.why or not self.points:
            return attrs.evolve(
                self.equations.solution,
                status=Status.NO_ROOT,
                message=self.why or "the response equations have no real root at these values",
            )
        if name is None:
            nontrivial = [
                i for i, p in enumerate(self.points) if not p.trivial and p.series_ok
            ] or [i for i, p in enumerate(self.points) if not p.trivial]
            index = nontrivial[-1] if nontrivial else len(self.points) - 1
        elif name in self.names:
            index = self.names.index(name)
        elif count_name(name):  # a branch that exists elsewhere, not here: a failed run
            return attrs.evolve(
                self.equations.solution,
                status=Status.NO_ROOT,
                message=(
                    f"no branch {name!r} at these values: the order-{self.equations.order} "
                    f"response has {list(self.names)} here (a branch ends at a fold: see "
                    "`perturb response` for where)"
                ),
            )
        else:
            raise UnknownNameError(
                f"`family` = {name!r} is not a branch of the response here: choose from "
                f"{list(self.names)}"
            )
        return branch_solution(self.equations, self.points[index], self.names[index])

    def families(self, system_name: str, order: int):
        """The branches as a :class:`perturb.FamilyList` (isolated families, by name)."""
        from perturb.method.families import Family, FamilyList

        families = [
            Family(
                name=name,
                kind="isolated",
                amplitudes={k: float(v) for k, v in point.amplitudes.items()},
                free=(),
                solution=branch_solution(self.equations, point, name),
                phase_coordinate=self.equations.coordinates[0],
            )
            for point, name in zip(self.points, self.names, strict=True)
        ]
        why = self.why or (
            "" if self.points else "the response equations have no real root here (proved)"
        )
        return FamilyList(system_name, order, 1, families, why=why)


def steady_state(
    system, values: Mapping, epsilon: float, order: int = 1, lower: SteadyState | None = None
) -> SteadyState:
    """Every branch of the driven ``system``'s response at ``values`` (:class:`SteadyState`).

    The branches are named by rank at order 1, the lowest order a command takes
    (:func:`branch_names`; the first-order equations, order 0, by rank too), and at order N > 1
    each inherits the name of its partner one order lower
    (:func:`perturb.steady.lineage.inherited_names`), so that a name picks the same orbit at
    every order. ``lower``: the order-(N−1) steady state at the same values, when the caller
    keeps it (else it is computed).
    """
    from perturb.method.driven import amplitude_equations
    from perturb.steady.census import shift_symmetry
    from perturb.steady.lineage import RANKED_ORDER, inherited_names

    equations = amplitude_equations(system, order)
    points, why, lowers = _branches(equations, values, epsilon, order)
    if order <= RANKED_ORDER or why:
        return SteadyState(points, branch_names(points, equations.harmonics), equations, why)
    if lower is None:
        lower = steady_state(system, values, epsilon, order - 1)
    if lower.why:  # no branches one order lower to inherit from: named by rank here
        return SteadyState(points, branch_names(points, equations.harmonics), equations, why)
    names = inherited_names(
        points, lowers, lower.points, lower.names, equations.harmonics, shift_symmetry(system)
    )
    return SteadyState(points, names, equations, why)
