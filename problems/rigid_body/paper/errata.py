"""The seed paper's errata: each claim with its status and the numbers that witness it.

Statuses: ``wrong`` (the claim is refuted by a derivation or a computation), ``confirmed``
(reproduced) and ``unverifiable`` (nothing in the paper allows a check).  The ids are those of
``docs/paper-errata.md``, which gives the full argument for each.

References
----------
.. [1] The seed paper, passim (the ``where`` field of each erratum).
.. [2] ``docs/paper-errata.md``.
"""

from __future__ import annotations

from problems.rigid_body.paper.closed_form import (
    deviation_with_phase,
    deviation_xa_d_dt,
    fit_table_frequency,
)
from problems.rigid_body.paper.data import PAPER_INPUTS, TABLE1_COLUMNS
from problems.rigid_body.paper.euler import EULER_EPSILONS
from problems.rigid_body.paper.witness import forcing_witnesses

__all__ = ["ERRATA_STATUSES", "EULER_WITNESS_CASE", "EULER_WITNESS_EPS", "errata", "euler_witness"]

#: The statuses of an erratum, in the order reports list them.
ERRATA_STATUSES = ("wrong", "confirmed", "unverifiable")

#: The Euler-angle witness: case and eps (an entry of EULER_EPSILONS) whose figures are quoted.
EULER_WITNESS_CASE = "k0.5_g0.3"
EULER_WITNESS_EPS = 0.01


def errata(
    consts: dict,
    cf: dict,
    printed: dict,
    check: dict,
    verdict: dict,
    exp: dict,
    euler: dict,
) -> dict:
    """Every erratum of the paper with its status, place, claim and witness.

    Parameters
    ----------
    consts : dict
        The derived constants (:func:`~problems.rigid_body.paper.data.derived_constants`).
    cf : dict
        The closed form's constants (:func:`~problems.rigid_body.paper.closed_form.closed_form`).
    printed : dict
        The printed Table 1.
    check : dict
        Table 1 against (30) (:func:`~problems.rigid_body.paper.closed_form.check_table`).
    verdict : dict
        The true motion's verdict (:func:`~problems.rigid_body.paper.truth.verdict`).
    exp : dict
        The RK4 experiment (:func:`~problems.rigid_body.paper.rk4_experiment.rk4_experiment`).
    euler : dict
        The Euler-angle study (:func:`~problems.rigid_body.paper.euler.euler_angle_study`).

    Returns
    -------
    dict
        ``id -> {"status", "where", "claim", "witness"}``.
    """
    wit = forcing_witnesses()
    d, p = wit["derived"], wit["paper"]
    w = {k: v for k, v in wit["values"].items()}
    runs = exp["runs"]
    p2a_t0_printed = printed["p2a"][0]
    return {
        "E1": {
            "status": "wrong",
            "where": "(4), (32)",
            "claim": "mu = c*sqrt(gamma0'')/r0 gives 0.615, not the printed 2.323554e6; 1e4*c/r0 "
            "reproduces it; the consistent parameter is eps = c/r0 = 232.4 (not small)",
            "witness": {
                "mu_definition": consts["mu"]["computed"],
                "mu_printed": consts["mu"]["printed"],
                "mu_1e4_c_over_r0": consts["mu_1e4_c_over_r0"]["computed"],
                "eps_c_over_r0": consts["eps"]["computed"],
            },
        },
        "E2": {
            "status": "wrong",
            "where": "title, abstract, sections 1-2, (1)-(2)",
            "claim": "the 'large parameter/slow spin' system is the fast-spin one with eps = 1/mu; "
            "for the paper's data the true motion is not approximated at all",
            "witness": verdict["numbers"],
        },
        "E3": {
            "status": "wrong",
            "where": "(26), (30), Table 1",
            "claim": "the factor mu^-1 in front of v1k*, v2k* implied by (19), (22), (23) is dropped",
            "witness": {
                "p2a_t0_printed": p2a_t0_printed,
                "v1_k_star": cf["v1_k_star"],
                "mu_inv_v1_k_star_printed_mu": cf["beta1_with_printed_mu"],
                "eps_v1_k_star": cf["beta1_with_eps"],
            },
        },
        "E4": {
            "status": "wrong",
            "where": "(30), Table 1",
            "claim": "Table 1 uses the phase h = T t/300 (not tau = r0 t) and xa, ya are d/dh, "
            "not d/dt as labelled",
            "witness": {
                "omega_T_over_300": cf["omega_table"],
                "omega_fit_from_table": fit_table_frequency(),
                "max_ratio_dev_over_tol": max(c["max_ratio"] for c in check.values()),
                "max_dev_h_r0t": deviation_with_phase(cf, PAPER_INPUTS["r0"]),
                "max_dev_xa_if_d_dt": deviation_xa_d_dt(cf),
            },
        },
        "E5a": {
            "status": "wrong",
            "where": "(21)",
            "claim": "gamma0'**2 in v1 must be y0'**2 (only that reading gives Table 1)",
            "witness": {
                "v1_k_star_with_y0p2": cf["v1_k_star"],
                "v1_k_star_with_gamma0p_literal": cf["v1_k_star_literal_gamma0p"],
                "p2a_t0_printed": p2a_t0_printed,
            },
        },
        "E5b": {
            "status": "wrong",
            "where": "(14)",
            "claim": "the first y0'**2 of L*33 must be x0'**2",
            "witness": {
                "F3_cos_derived": d["F3_cos"],
                "L33_M3_as_printed": p["F3_cos_printed"],
                "L33_M3_with_x0p2": p["F3_cos_x0p_fix"],
                "values": w,
            },
        },
        "E5c": {
            "status": "wrong",
            "where": "(5)",
            "claim": "p1 = p/c**2 must be p1 = p/c (only p = c p1 makes (1)-(3), (24), (26) "
            "dimensionless in the stated form)",
            "witness": {"see": "docs/paper-errata.md E5c (symbolic check)"},
        },
        "E6": {
            "status": "wrong",
            "where": "(10), (12), (20), (21), (23), (27)",
            "claim": "Phi2: N*21 has k C1 M3^2 for k C1 M3^2/2 and spurious -a(M1^2-M2^2)M3/4 cos, "
            "-a M1 M2 M3/2 sin terms; hence alpha (20) and k* = 2/(k(C1+1)M3^2) are wrong "
            "(correct: k* = 1/(k M3^2))",
            "witness": {
                "Phi2_cos_derived": d["Phi2_cos"],
                "Phi2_cos_paper": p["Phi2_cos"],
                "Phi2_sin_derived": d["Phi2_sin"],
                "Phi2_sin_paper": p["Phi2_sin"],
                "alpha_over_eps2_derived": d["alpha_over_eps2"],
                "alpha_over_eps2_paper": p["alpha_over_eps2"],
                "detuning_derived": d["detuning"],
                "detuning_paper": p["detuning"],
                "values": w,
            },
        },
        "E7": {
            "status": "wrong",
            "where": "(19), (23), (26)",
            "claim": "beta1 is too large by 1/b and beta2 has the wrong sign: correct "
            "beta1 = b * paper's, beta2 = -b * paper's",
            "witness": {
                "beta1_over_eps_derived": d["beta1_over_eps"],
                "beta1_over_eps_paper": p["beta1_over_eps"],
                "beta2_over_eps_derived": d["beta2_over_eps"],
                "beta2_over_eps_paper": p["beta2_over_eps"],
                "b": w["b"],
            },
        },
        "E8": {
            "status": "wrong",
            "where": "(6), (24)",
            "claim": "(24) has 'a k' where the disk needs 'k'; (6)'s O(1/mu) bracket is the "
            "constant a p20 g20 - b p20' g20' (correct, but carries no dynamics)",
            "witness": {"see": "docs/paper-errata.md E8 (symbolic check)"},
        },
        "E9": {
            "status": "unverifiable",
            "where": "(31), (32)",
            "claim": "chi2 is undefined in the text (it equals -k gamma0''); lambda = 0.6 and "
            "T = 18.78775142 have no derivation",
            "witness": {
                "chi2_computed": consts["chi2"]["computed"],
                "chi2_printed": consts["chi2"]["printed"],
                "T": PAPER_INPUTS["T"],
                "lambda": PAPER_INPUTS["lambda"],
            },
        },
        "E10": {
            "status": "wrong",
            "where": "(33), section 4.2",
            "claim": "(33) multiplies F2, Phi2 by mu^2 where (1) has mu^-2; with mu^2 RK4 blows up, "
            "with mu^-2 the forcing is 1e-13 and RK4 returns Table 1: the experiment cannot test "
            "the theory",
            "witness": {
                "mu2_h_reached": runs["printed_mu_squared"].get("h_reached"),
                "mu_minus_2_max_diff_vs_table1": runs["mu_minus_2"].get("max_diff_vs_table1"),
                "mu_minus_2_max_diff_vs_true_motion": runs["mu_minus_2"].get(
                    "max_diff_vs_true_motion"
                ),
            },
        },
        "E11": {
            "status": "wrong",
            "where": "(27)",
            "claim": "tau = r0^-1 t must be tau = r0 t (r0 is a rate; d/dt = r0 d/dtau)",
            "witness": {"see": "docs/paper-errata.md E11"},
        },
        "C1": {
            "status": "confirmed",
            "where": "(32)",
            "claim": "C1, ell, x0', y0', c (with g = 1.5e-7), a, b, k, chi2 reproduce to all "
            "printed digits",
            "witness": {
                n: consts[n]["matches"]
                for n in ("C1", "ell", "x0p", "y0p", "c", "a", "b", "k", "chi2")
            },
        },
        "C2": {
            "status": "confirmed",
            "where": "(10), (12)",
            "claim": "F2's first harmonic is M1 L*21 cos + M2 L*21 sin with L*21 as printed",
            "witness": {
                "F2_cos_derived": d["F2_cos"],
                "F2_cos_paper": p["F2_cos"],
                "F2_sin_derived": d["F2_sin"],
                "F2_sin_paper": p["F2_sin"],
                "values": w,
            },
        },
        "C3": {
            "status": "confirmed",
            "where": "(11), (13)",
            "claim": "L*34 (sin coefficient of F3 at M1 = M2 = 0) as printed",
            "witness": {"F3_sin_derived": d["F3_sin"], "F3_sin_paper": p["F3_sin"], "values": w},
        },
        "C4": {
            "status": "confirmed",
            "where": "(30), Table 1",
            "claim": "Table 1 is (30) evaluated at h = T t/300 to the printed precision",
            "witness": {c: check[c]["max_deviation_7_digit_rows"] for c in TABLE1_COLUMNS},
        },
        "U1": {
            "status": "unverifiable",
            "where": "section 4.2",
            "claim": "Table 2 (the paper's RK4 results) is not printed",
            "witness": {},
        },
        "E12": {
            "status": "wrong",
            "where": "(26), (28), (29)",
            "claim": "the Euler angles fail at leading order in the fast-spin regime: theta misses "
            "the amplitude (beta) terms of the nutation, psi is O(eps) where the precession is "
            "O(eps^2) (a factor c/r0 is missing), phi has spurious O(eps) terms and lacks the "
            "O(eps^2) rate correction (see docs/paper-errata.md E12)",
            "witness": euler_witness(euler),
        },
    }


def euler_witness(euler: dict) -> dict:
    """Key figures of the Euler-angle check for E12 (one case, one eps, and the slopes)."""
    block = euler[EULER_WITNESS_CASE]
    i = EULER_EPSILONS.index(EULER_WITNESS_EPS)
    pairs = ("true_vs_paper", "true_vs_ours", "true_vs_leading_order")
    return {
        "case": {"k": block["k"], "gamma3_0": block["gamma3_0"], "eps": block["eps"][i]},
        "true_size": {a: v[i] for a, v in block["size"].items()},
        **{pair: {a: v[i] for a, v in block["max_diff"][pair].items()} for pair in pairs},
        "slopes": {pair: block["slope"][pair] for pair in ("size", *pairs)},
    }
