"""The disk's families (issue 11, item 4): the branch M1 = M2 = 0 and the circle M1² + M2² = k M3².

docs/problems/disk-second-family.md derives the order-2 amplitude equations by hand:
a_P0 (2(a_P0² + b_P0²) - k M3²) = 0 and the same with b_P0, so the families are the point
a_P0 = b_P0 = 0 (the paper's branch, the default of ``perturb solve disk``) and the circle of radius²
k M3², which does not survive order 3 as a family (only two points of it do).
"""

from __future__ import annotations

import pytest
import sympy as sp

from perturb import Status
from problems import get_problem

pytestmark = pytest.mark.slow  # the symbolic order-2 amplitude equations of the disk: ~25 s


@pytest.fixture(scope="module")
def disk():
    return get_problem("disk").create()


def test_disk_families_are_the_paper_branch_and_the_circle(disk):
    families = disk.families(1)
    assert families.family_order == 2  # the disk's forcing starts at eps**2
    assert set(families.names) == {"G-line", "circle-1", "circle-2"}
    line = families.get("G-line")
    assert line.kind == "isolated"
    assert line.amplitudes["a_P"] == 0 and line.amplitudes["b_P"] == 0
    assert line.status is Status.SUCCESS
    k, gamma3_0, a_p = sp.symbols("k gamma3_0 a_P")
    for name in ("circle-1", "circle-2"):
        circle = families.get(name)
        assert circle.kind == "continuum" and circle.free == ("a_P",)
        radius2 = (
            sp.sympify(circle.amplitudes["a_P"]) ** 2 + sp.sympify(circle.amplitudes["b_P"]) ** 2
        )
        assert sp.simplify(radius2 - k * (1 - gamma3_0**2)) == 0
        # a generic point of the circle is not a periodic orbit at order 3
        assert circle.status is Status.INCONSISTENT and circle.message.startswith("order 3")


def test_g_line_is_the_branch_the_disk_used(disk):
    before = disk.solve(1)
    chosen = disk.case().with_family("G-line").model.solve(1)
    for row_a, row_b in zip(before.terms, chosen.terms, strict=True):
        for ta, tb in zip(row_a, row_b, strict=True):
            assert (ta - tb).expand().is_zero()
    assert all(
        sp.simplify(p - q) == 0 for p, q in zip(before.frequency, chosen.frequency, strict=True)
    )
