"""Reproduction of the seed paper (``perturb reproduce paper``): Table 1, constants (32), errata.

Paper: "periodic solutions of a disk about a fixed point in a Newtonian force field and gravity"
(large parameter technique); Table 1 from the shipped copy ``problems/rigid_body/data/table1.csv``.
Every erratum with a numeric witness is asserted here (ids as in ``docs/paper-errata.md``).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from perturb.cli import main
from perturb.errors import InvalidParameterError, UnknownNameError
from problems.rigid_body.paper import (
    KNOWN_PAPERS,
    TABLE1_COLUMNS,
    paper_table1,
    reproduce,
)
from problems.rigid_body.paper import reproduction as paper_reproduction
from problems.rigid_body.paper.data import table1_tolerance

pytestmark = pytest.mark.paper

PRINTED = paper_table1()
ROWS = range(len(PRINTED["t"]))


@pytest.fixture(scope="module")
def report():
    return reproduce("paper")


# ---------------------------------------------------------------------------- Table 1
@pytest.mark.parametrize("row", ROWS, ids=[f"t={t:g}" for t in PRINTED["t"]])
@pytest.mark.parametrize("column", TABLE1_COLUMNS)
def test_table1_entry(report, column, row):
    """Each printed entry is the closed form (30) at h = T t/300 within its printed precision."""
    text = PRINTED[column + "_text"][row]
    assert abs(report.table1[column][row] - float(text)) <= table1_tolerance(text)


def test_table1_tolerance_rule():
    assert table1_tolerance("2.79E-01") == pytest.approx(0.0005)  # 0.279: last digit 1e-3
    assert table1_tolerance("7.048539") == pytest.approx(1e-5)  # floor
    assert table1_tolerance("1") == pytest.approx(1e-5)  # %.7g dropped the zeros


def test_table1_shipped_copy_is_complete():
    assert PRINTED["t"] == [10.0 * i for i in range(31)]
    assert PRINTED["p2a_text"][2] == "2.79E-01"


# ---------------------------------------------------------------------------- constants (32)
@pytest.mark.parametrize("name", ["C1", "ell", "x0p", "y0p", "g", "c", "a", "b", "k", "chi2"])
def test_constant_reproduced(report, name):
    row = report.constants[name]
    assert row["matches"], row


def test_mu_does_not_follow_from_its_definition(report):
    """E1: mu = c sqrt(gamma0'')/r0 = 0.615, printed 2.323554e6 = 1e4 c/r0."""
    mu = report.constants["mu"]
    assert not mu["matches"]
    assert mu["computed"] == pytest.approx(0.61475, abs=1e-5)
    assert report.constants["mu_1e4_c_over_r0"]["matches"]
    assert report.constants["eps"]["computed"] == pytest.approx(232.3554, abs=1e-4)


# ---------------------------------------------------------------------------- errata witnesses
def test_e2_true_motion_is_not_approximated(report):
    n = report.verdict["numbers"]
    assert not report.verdict["valid"]
    assert n["r_over_r0_min_0_300s"] == pytest.approx(-229.4, abs=0.1)
    assert n["max_abs_dp2_table_rows"] > 10
    assert n["max_abs_dgamma2_table_rows"] > 1.5
    drift = report.table2["true_motion"]["relative_integral_drift"]
    assert max(drift.values()) < 1e-10  # the oracle itself is trustworthy


def test_e3_table_drops_the_inverse_mu(report):
    w = report.errata["E3"]["witness"]
    assert w["v1_k_star"] == pytest.approx(w["p2a_t0_printed"], abs=1e-6)
    assert w["mu_inv_v1_k_star_printed_mu"] < 1e-5
    assert w["eps_v1_k_star"] == pytest.approx(1637.8, abs=0.1)


def test_e4_table_phase_is_T_t_over_300(report):
    w = report.errata["E4"]["witness"]
    assert w["omega_fit_from_table"] == pytest.approx(w["omega_T_over_300"], rel=1e-7)
    assert w["max_ratio_dev_over_tol"] < 1
    assert w["max_dev_h_r0t"] > 1  # tau = r0 t does not give the table
    assert w["max_dev_xa_if_d_dt"] > 5  # xa labelled d/dt is really d/dh


def test_e5a_gamma0p_must_be_y0p(report):
    w = report.errata["E5a"]["witness"]
    assert w["v1_k_star_with_y0p2"] == pytest.approx(7.048539, abs=1e-6)
    assert w["v1_k_star_with_gamma0p_literal"] < 0


def test_e5b_first_square_of_l33_is_x0p(report):
    w = report.errata["E5b"]["witness"]
    assert w["F3_cos_derived"] == pytest.approx(w["L33_M3_with_x0p2"], rel=1e-10)
    assert abs(w["F3_cos_derived"] - w["L33_M3_as_printed"]) > 0.1


def test_e5c_p1_is_p_over_c():
    """Only p = c p1 cancels c from the dimensionless Euler equation for p1 (tau = r0 t)."""
    import sympy as sp

    from problems.rigid_body import equations as eq

    p1, c, r0 = eq.p1, eq.c, eq.r0

    def leftover(scale):
        rhs = eq.euler_poisson_equations()[0].subs(
            {eq.p: scale * p1, eq.q: scale * eq.q1, eq.r: r0 * eq.r1}
        ) / (scale * r0)
        expr = sp.expand(sp.cancel(rhs.subs(eq.nondimensional_substitution())))
        return expr.subs(c, sp.Symbol("epsilon") * r0).free_symbols & {c, r0}

    assert not leftover(c)
    assert leftover(c**2)


def test_e6_phi2_and_period_correction(report):
    w = report.errata["E6"]["witness"]
    v = w["values"]
    a, b, k, x, g3 = v["a"], v["b"], v["k"], v["x0p"], v["gamma3_0"]
    m1, m2, m3 = v["M1"], v["M2"], v["M3"]
    correct = m3 * (-a * m1**2 - b * m2**2 + 2 * m3 * x + k * (g3**2 + 0.5 * (b - a) * m3**2))
    assert w["Phi2_cos_derived"] == pytest.approx(correct, rel=1e-12)
    assert abs(w["Phi2_sin_derived"]) < 1e-12
    assert abs(w["Phi2_cos_paper"] - w["Phi2_cos_derived"]) > 1e-2
    assert abs(w["Phi2_sin_paper"]) > 1e-2
    # alpha differs by exactly pi * k C1 M3^2 / 2
    gap = w["alpha_over_eps2_paper"] - w["alpha_over_eps2_derived"]
    assert gap == pytest.approx(math.pi * 0.5 * k * (b - a) * m3**2, rel=1e-9)
    assert w["detuning_derived"] == pytest.approx(0.5 * k * m3**2, rel=1e-6)


def test_e7_amplitudes_b_times_and_sign(report):
    w = report.errata["E7"]["witness"]
    b = w["b"]
    assert w["beta1_over_eps_derived"] == pytest.approx(b * w["beta1_over_eps_paper"], rel=1e-6)
    assert w["beta2_over_eps_derived"] == pytest.approx(-b * w["beta2_over_eps_paper"], rel=1e-6)


def test_e8_q1_first_order_has_k_not_ak():
    import sympy as sp

    from perturb.system import EPS
    from problems.rigid_body.reduction import disk_reduction

    red = disk_reduction(2)
    a, k, y0p = sp.symbols("a k y0p")
    g30, dg = sp.Symbol("gamma3_0"), sp.Symbol("dG")
    coeff = sp.expand(red.full_state[1]).coeff(EPS, 1)
    assert sp.simplify(coeff - g30 * (y0p / a + k * dg)) == 0
    assert sp.simplify(coeff - g30 * (y0p / a + a * k * dg)) != 0


def test_e8_integral_bracket_is_constant():
    """(6)-(7): a p2 g2 - b p2' g2' + s21 = a p20 g20 - b p20' g20' identically."""
    import sympy as sp

    a, b, p, g, dp, dg, p0, g0, dp0, dg0 = sp.symbols("a b p g dp dg p0 g0 dp0 dg0")
    s21 = a * (p0 * g0 - p * g) - b * (dp0 * dg0 - dp * dg)
    assert sp.expand(a * p * g - b * dp * dg + s21 - (a * p0 * g0 - b * dp0 * dg0)) == 0


def test_e10_experiment_33(report):
    runs = report.experiment["runs"]
    assert runs["printed_mu_squared"]["status"] < 0  # mu^2 as printed: blow-up
    assert runs["printed_mu_squared"]["h_reached"] < 0.01
    close = runs["mu_minus_2"]["max_diff_vs_table1"]
    assert max(close.values()) < 5e-4  # mu^-2: RK4 just returns Table 1
    assert runs["mu_minus_2"]["max_diff_vs_true_motion"]["p2a"] > 10


def test_confirmed_f2_l21_and_l34(report):
    c2, c3 = report.errata["C2"]["witness"], report.errata["C3"]["witness"]
    assert c2["F2_cos_derived"] == pytest.approx(c2["F2_cos_paper"], rel=1e-12)
    assert c2["F2_sin_derived"] == pytest.approx(c2["F2_sin_paper"], rel=1e-12)
    assert c3["F3_sin_derived"] == pytest.approx(c3["F3_sin_paper"], rel=1e-12)


def test_errata_statuses(report):
    statuses = {e["status"] for e in report.errata.values()}
    assert statuses == {"wrong", "confirmed", "unverifiable"}
    for eid in ("E1", "E2", "E3", "E4", "E5a", "E5b", "E5c", "E6", "E7", "E8", "E9"):
        assert eid in report.errata


# ---------------------------------------------------------------------------- API and CLI
def test_report_is_serialisable(report):
    # its run time is measured in benchmarks/bench_disk.py, never asserted here (machine load varies)
    assert report.elapsed > 0
    data = json.loads(json.dumps(report.as_dict(), allow_nan=True))
    assert "Verdict" in report.as_table()
    assert data["table2"]["true_motion"]["t"][-1] == 300


def test_unknown_paper():
    with pytest.raises(UnknownNameError, match="paper"):
        reproduce("nope")


def test_cli_json_keys(capsys):
    assert main(["reproduce", "paper", "--format", "json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {"constants", "table1", "table2", "experiment", "verdict", "errata"} <= set(data)
    assert set(data["table1"]) == {"t", *TABLE1_COLUMNS}
    for name in ("c", "k", "ell", "x0p", "y0p", "a", "b", "C1", "mu", "chi2"):
        assert {"computed", "printed", "matches"} <= set(data["constants"][name])
    assert np.isfinite(data["table2"]["true_motion"]["p2a"]).all()


def test_cli_unknown_paper_exit_2(capsys):
    assert main(["reproduce", "nope"]) == 2
    err = capsys.readouterr().err
    assert all(name in err for name in KNOWN_PAPERS)


def test_cli_unwritable_output_exit_2(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["reproduce", "paper", "--output", str(blocker / "sub")]) == 2
    err = capsys.readouterr().err.strip()
    assert "--output" in err and len(err.splitlines()) == 1


def test_unwritable_output_raises_before_work(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    monkeypatch.setattr(
        paper_reproduction, "derived_constants", lambda: pytest.fail("work started")
    )
    with pytest.raises(InvalidParameterError, match="writable"):
        reproduce("paper", output=blocker)


def test_output_files(tmp_path):
    reproduce("paper", output=tmp_path / "out")
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert names == {"paper-report.json", "constants.csv", "table1.csv", "table2.csv", "errata.csv"}
    first = (tmp_path / "out" / "table1.csv").read_text().splitlines()[0]
    assert first.startswith("t,p2a,p2a_printed")
