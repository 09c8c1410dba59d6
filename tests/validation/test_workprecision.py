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


def test_each_point_is_warmed_up_then_timed_at_its_best(monkeypatch):
    """Issue 21.4: a point's one-time costs (imports, JIT, first-use caches) are paid by an untimed
    warm-up call, and the best of the timed calls is reported. A fake clock makes it exact: the
    first call of ``fn`` costs 100 s, the later ones 3, 1 and 2 s."""
    import perturb.workprecision as wp

    clock = {"now": 0.0}
    costs = iter([100.0, 3.0, 1.0, 2.0])
    calls = []

    def fn():
        calls.append(clock["now"])
        clock["now"] += next(costs)
        return len(calls)

    monkeypatch.setattr(wp.time, "perf_counter", lambda: clock["now"])
    seconds, result = wp._best_time(fn, repeat=3)
    assert len(calls) == 4  # one warm-up + three timed
    assert seconds == 1.0  # the best timed call; the 100 s warm-up is in no figure
    assert result == 4


def test_a_converging_method_falls_monotonically_as_its_setting_tightens():
    """The error of DOP853 and of RK4 falls at every step of their settings (deterministic: the
    error does not depend on the timing)."""
    table = work_precision(
        get_problem("duffing").create(eps=0.1),
        periods=3,
        orders=1,
        rk4_steps=(10, 20, 40, 80),
        scipy_methods=("DOP853",),
        tolerances=(1e-6, 1e-8, 1e-10, 1e-12),
        heyoka=False,
        repeat=1,
    )
    for method in ("rk4", "scipy DOP853"):
        errors = [p.error for p in table.points if p.method == method]
        assert len(errors) == 4
        assert all(b < a for a, b in zip(errors, errors[1:], strict=False)), (method, errors)
