"""``numpy_lambdify`` builds the function ``sympy.lambdify(..., "numpy")`` builds, more cheaply."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from hypothesis import given
from hypothesis import strategies as st

from perturb._lambdify import numpy_lambdify

x, y, z = sp.symbols("x y z")
ROOT = Path(__file__).resolve().parents[2]

CASES = [
    ([x, y], [sp.sin(x) ** 2 + sp.sqrt(x * y) + sp.Rational(1, 3) * x**5, sp.cos(y) * sp.sin(x)]),
    ((x, (y, z)), sp.Matrix([[sp.Abs(x), sp.atan2(y, z)], [sp.exp(x) + sp.pi, sp.Heaviside(x)]])),
    ((x, y, z), sp.I * x + sp.Float("1.5") * y**3 - sp.Rational(2, 7) * sp.log(z)),
    ([(x, y), ()], [x * y, sp.Max(x, y) + sp.Min(x, y) ** sp.Rational(3, 2)]),
]


def _source(function) -> str:
    import inspect

    return re.sub(r"_Dummy_\d+", "_Dummy", inspect.getsource(function))


@pytest.mark.parametrize("cse", [False, True])
@pytest.mark.parametrize("args, expr", CASES)
def test_same_source_and_names_as_sympy_numpy(args, expr, cse):
    ours = numpy_lambdify(args, expr, cse=cse)
    theirs = sp.lambdify(args, expr, "numpy", cse=cse)
    assert _source(ours) == _source(theirs)
    # every name the generated code can reach is bound to the very same object
    for name, value in ours.__globals__.items():
        if not name.startswith("_") and name in theirs.__globals__:
            assert theirs.__globals__[name] is value, name
    # and nothing sympy's namespace offers is missing, but numpy's not-yet-imported submodules
    missing = set(theirs.__globals__) - set(ours.__globals__)
    assert all(not hasattr(np, "__all__") or name in np.__all__ for name in missing), missing


coefficients = st.fractions(min_value=-5, max_value=5, max_denominator=9)


@given(st.lists(coefficients, min_size=1, max_size=6), st.floats(-3, 3), st.floats(0.1, 3))
def test_same_numbers_to_the_bit(coeffs, xv, yv):
    expr = [
        sum(
            sp.Rational(c.numerator, c.denominator) * x**i * y ** (i % 3)
            for i, c in enumerate(coeffs)
        ),
        sp.cos(x) * sp.sqrt(y) + sp.Rational(coeffs[0].numerator, 7) * sp.sin(x * y),
    ]
    ours = np.asarray(numpy_lambdify((x, y), expr, cse=True)(xv, yv))
    theirs = np.asarray(sp.lambdify((x, y), expr, "numpy", cse=True)(xv, yv))
    assert ours.tobytes() == theirs.tobytes()


def test_does_not_import_numpy_submodules_it_never_calls():
    code = (
        "import sys, sympy; from perturb._lambdify import numpy_lambdify; "
        "x = sympy.Symbol('x'); print(numpy_lambdify(x, sympy.sin(x))(0.0)); "
        "print(sorted(m for m in ('numpy.f2py', 'numpy.testing') if m in sys.modules))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT,
        env={"PYTHONPATH": str(ROOT), "PATH": ""},
    ).stdout.split()  # fmt: skip
    assert out == ["0.0", "[]"]


def test_integers_beyond_int64_reach_numpy_functions_as_their_nearest_doubles():
    """A specialised disk solution holds sqrt(847504615198858776185891631): as a Python int in
    the generated code numpy's sqrt failed on it (``perturb validate disk --set r0=0.5 --set
    gamma3_0=0.1424... --order 2`` was an internal error). Each value is checked against exact
    arithmetic; where such an integer worked before (a product) the number is the same bits."""
    n = sp.Integer(847504615198858776185891631)
    f = numpy_lambdify(x, [sp.sqrt(n) * x, n * x, sp.exp(-n / n) + sp.cos(x)], cse=True)
    at = np.array([1.0, 3.0])
    root, product, small = f(at)
    exact_root = sp.sqrt(n).evalf(40)
    for value, point in zip(root, at, strict=True):
        assert abs(value - float(exact_root * sp.Float(point, 40))) <= 1e-16 * abs(value)
    assert list(product) == [float(n) * 1.0, float(n) * 3.0]  # what Python's int * float makes
    np.testing.assert_array_equal(small, np.exp(-1.0) + np.cos(at))
