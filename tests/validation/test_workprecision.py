"""work_precision(): table shape, error ordering, bad input (issue 4 item 2)."""

import math

import pytest

from perturb.errors import InvalidParameterError
from perturb.report import work_precision_as_csv
from perturb.workprecision import work_precision
from problems import get_problem


@pytest.fixture(scope="module")
def table():
    return work_precision(
        get_problem("duffing").create(eps=0.1),
        periods=3,
        orders=2,
        rk4_steps=(20, 80),
        scipy_methods=("DOP853",),
        tolerances=(1e-6, 1e-10),
        repeat=1,
    )


def test_rows_and_csv(table):
    csv = work_precision_as_csv(table).splitlines()
    assert csv[0] == "method,setting,error,seconds"
    methods = {p.method for p in table.points}
    assert {"analytic", "analytic derivation", "rk4", "scipy DOP853"} <= methods
    assert len(csv) == len(table.points) + 1
    assert all(p.seconds >= 0 for p in table.points)


def test_errors_decrease_with_effort(table):
    by = {(p.method, p.setting): p.error for p in table.points}
    assert by[("analytic", "order 2")] < by[("analytic", "order 1")] / 5  # O(eps^2) -> O(eps^3)
    assert by[("rk4", "80 steps/unit")] < by[("rk4", "20 steps/unit")] / 100  # 4^4 = 256
    assert by[("scipy DOP853", "rtol=1e-10")] < by[("scipy DOP853", "rtol=1e-06")]
    assert math.isnan(by[("analytic derivation", "order 1")])


def test_plot_or_clear_import_error(table):
    from perturb.report.plots import plot_work_precision

    try:
        import matplotlib  # noqa: F401
    except ImportError:
        with pytest.raises(ImportError, match="matplotlib"):
            plot_work_precision(table)
    else:
        assert plot_work_precision(table) is not None


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"periods": 0}, "periods"),
        ({"repeat": 0}, "repeat"),
        ({"tolerances": (1e-8, -1.0)}, "tolerances"),
        ({"rk4_steps": (0,)}, "rk4_steps"),
        ({"orders": 0}, "orders"),
    ],
)
def test_bad_input(kwargs, name):
    with pytest.raises(InvalidParameterError, match=f"`{name}`"):
        work_precision(get_problem("duffing").create(), **kwargs)
