"""Issue 22, done when: ``perturb families`` on a resonant chain written in a user's own file lists
every branch, each named by its mode shape, with its frequency series.

The file is written the way a user would write it (the equations typed in, nothing imported from
``problems.resonant_chain``); the counts are msolve's proved counts, which ``tests/algebra/test_chain.py``
checks against Newton on the whole system and ``benchmarks/bench_chain.py`` against sympy and a homotopy.
"""

from __future__ import annotations

import json
import textwrap

import pytest
import sympy as sp

from perturb.cli import main

_CHAIN_FILE = '''
import sympy as sp

from perturb import EPS, QuasilinearSystem
from problems.base import ParameterSpec, Problem, positive


class Chain(Problem):
    """x_i'' + x_i = -eps [(x_i - x_(i-1))^3 + (x_i - x_(i+1))^3], ends fixed, x1(0) = amplitude."""

    name = "my-chain-{n}"
    summary = "my chain of {n} cubic springs"
    parameter_specs = (
        ParameterSpec("eps", 0.01, "spring strength"),
        ParameterSpec("amplitude", 1.0, "x1(0)", positive),
    )

    @classmethod
    def build_system(cls):
        x = [sp.Symbol(f"x{{i}}") for i in range(1, {m})]
        v = [sp.Symbol(f"x{{i}}dot") for i in range(1, {m})]
        ends = [0, *x, 0]
        rhs = [
            -EPS * ((ends[i] - ends[i - 1]) ** 3 + (ends[i] - ends[i + 1]) ** 3)
            for i in range(1, {m})
        ]
        return QuasilinearSystem(x, v, [1] * {n}, rhs)

    def method_options(self):
        return {{"amplitudes": {{"x1": sp.Integer(1)}}}}
'''

#: Branches of the chain of n at order 1, x1's amplitude 1 (proved by msolve; five and eight).
BRANCHES = {3: 5, 4: 8}


def _families(capsys, tmp_path, n):
    path = tmp_path / f"my_chain_{n}.py"
    path.write_text(textwrap.dedent(_CHAIN_FILE.format(n=n, m=n + 1)))
    code = main(["families", f"{path}:Chain", "--order", "1", "--format", "json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out)["families"]


@pytest.mark.parametrize("n", sorted(BRANCHES))
def test_every_branch_of_a_users_chain_is_listed_and_named(capsys, tmp_path, n):
    families = _families(capsys, tmp_path, n)
    assert len(families) == BRANCHES[n]
    assert all(f["status"] == "SUCCESS" and f["kind"] == "isolated" for f in families)
    names = [f["name"] for f in families]
    assert len(set(names)) == len(names)
    assert "in-phase" in names
    assert any(name.startswith("anti-phase") for name in names)
    for family in families:
        # the frequency series: 1 at order 0, a non-zero shift at order 1 (every spring is hard)
        assert family["frequency"][0] == 1
        assert sp.sympify(family["frequency"][1]).is_positive


def test_the_in_phase_branch_moves_every_mass_one_way(capsys, tmp_path):
    families = {f["name"]: f for f in _families(capsys, tmp_path, 3)}
    amplitudes = families["in-phase"]["amplitudes"]
    cosines = [sp.sympify(amplitudes[f"a_x{i}"]) for i in (1, 2, 3)]
    assert all(c.is_positive for c in cosines)
    assert all(sp.sympify(amplitudes.get(f"b_x{i}", 0)) == 0 for i in (2, 3))
    # the chain's mirror symmetry: the ends move alike on the in-phase branch
    assert sp.simplify(cosines[0] - cosines[2]) == 0
