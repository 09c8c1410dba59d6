"""The paper's closed form (30) with its amplitudes (21)–(23): a CLAIM UNDER TEST, and its Table 1.

This module is the one place where the printed closed form is encoded on purpose: it is the claim
being reproduced, not a result of the project.  It recomputes Table 1 from (30) and measures how
well the printed table agrees, and how it does not under the other readings of its phase (E4).

References
----------
.. [1] The seed paper, equations (21), (23), (30) and Table 1.
.. [2] Reference derivation ``derivation.md``, section (e).
"""

from __future__ import annotations

import numpy as np

from problems.rigid_body.paper.data import (
    PAPER_INPUTS,
    PRINTED_CONSTANTS,
    TABLE1_COLUMNS,
    TABLE1_T_END,
    paper_scaled,
    paper_table1,
    table1_tolerance,
)

__all__ = [
    "check_table",
    "closed_form",
    "closed_form_columns",
    "deviation_with_phase",
    "deviation_xa_d_dt",
    "fit_table_frequency",
]


def closed_form() -> dict[str, float]:
    """v1, v2, k* of (21), (23) as printed (M3 = 1 by (25)), under both readings of gamma0'.

    Returns
    -------
    dict
        ``M3, k_star, k_star_corrected, v1, v2, v1_k_star, v2_k_star, v1_literal_gamma0p,
        v1_k_star_literal_gamma0p, beta1_with_printed_mu, beta1_with_eps, omega_table`` (the
        table's phase rate T/300).
    """
    nd = paper_scaled()
    a, b, k, x, y = nd.a, nd.b, nd.k, nd.x0p, nd.y0p
    g3, m3 = PAPER_INPUTS["gamma3_0"], 1.0
    c1 = b - a
    k_star = 2 / (k * (c1 + 1) * m3**2)  # (23): l1 = v1 k*, k* = 2/(k (C1 + 1) M3^2)
    v2 = -6 * m3 * g3 * x * y / (a * b)

    def v1_with(square: float) -> float:
        # (21): v1 = M3 g0'' [2 a^-2 (a+1) (square) - 2 b^-2 (b+1) x0'^2 + a k^2 M3^2]
        return (
            m3 * g3 * (2 * (a + 1) * square / a**2 - 2 * (b + 1) * x**2 / b**2 + a * k**2 * m3**2)
        )

    v1 = v1_with(y**2)
    # Literal reading: gamma0' is the initial gamma', which (26) makes ~0 (3e-12).
    v1_literal = v1_with(0.0)
    mu = float(PRINTED_CONSTANTS["mu"])
    return {
        "M3": m3,
        "k_star": k_star,
        "k_star_corrected": 1 / (k * m3**2),
        "v1": v1,
        "v2": v2,
        "v1_k_star": v1 * k_star,
        "v2_k_star": v2 * k_star,
        "v1_literal_gamma0p": v1_literal,
        "v1_k_star_literal_gamma0p": v1_literal * k_star,
        "beta1_with_printed_mu": v1 * k_star / mu,
        "beta1_with_eps": v1 * k_star * nd.eps,
        "omega_table": PAPER_INPUTS["T"] / TABLE1_T_END,
    }


def closed_form_columns(t: np.ndarray, cf: dict) -> dict[str, np.ndarray]:
    """The paper's (30) at the phase h = T t/300 (reference (e)); xa, ya are d/dh.

    Parameters
    ----------
    t : numpy.ndarray
        The table's time column.
    cf : dict
        The output of :func:`closed_form` (``omega_table`` sets the phase rate).

    Returns
    -------
    dict
        ``{"p2a", "gamma2a", "xa", "ya"}`` arrays shaped like ``t``.
    """
    h = cf["omega_table"] * t
    u, v = cf["v1_k_star"], cf["v2_k_star"]
    return {
        "p2a": u * np.cos(h) + v * np.sin(h),
        "gamma2a": np.cos(h),
        "xa": -u * np.sin(h) + v * np.cos(h),
        "ya": -np.sin(h),
    }


def check_table(computed: dict, printed: dict) -> dict:
    """Per column: max deviation, max deviation/tolerance, rows outside the printed precision.

    Parameters
    ----------
    computed : dict
        Table 1 columns recomputed (:func:`closed_form_columns`).
    printed : dict
        The printed table (:func:`~problems.rigid_body.paper.data.paper_table1`).

    Returns
    -------
    dict
        ``column -> {"max_deviation", "max_deviation_7_digit_rows", "max_ratio", "rows_outside"}``.
    """
    out = {}
    for col in TABLE1_COLUMNS:
        dev = np.abs(np.asarray(computed[col]) - np.asarray(printed[col]))
        tol = np.array([table1_tolerance(s) for s in printed[col + "_text"]])
        plain = np.array(["e" not in s.lower() for s in printed[col + "_text"]])
        out[col] = {
            "max_deviation": float(dev.max()),
            "max_deviation_7_digit_rows": float(dev[plain].max()),
            "max_ratio": float((dev / tol).max()),
            "rows_outside": [printed["t"][i] for i in np.flatnonzero(dev > tol)],
        }
    return out


def fit_table_frequency() -> float:
    """Least-squares frequency w of gamma2a = cos(w t), ya = -sin(w t) from the printed Table 1."""
    from scipy.optimize import least_squares

    printed = paper_table1()
    t = np.asarray(printed["t"])
    g, y = np.asarray(printed["gamma2a"]), np.asarray(printed["ya"])

    def residual(x):
        return np.concatenate((np.cos(x[0] * t + x[1]) - g, -np.sin(x[0] * t + x[1]) - y))

    return float(least_squares(residual, [0.06, 0.0], xtol=1e-15, ftol=1e-15).x[0])


def deviation_with_phase(cf: dict, omega: float) -> float:
    """Max |(30) - Table 1| over all columns when the phase is ``omega * t`` instead of T t/300."""
    printed = paper_table1()
    t = np.asarray(printed["t"])
    cols = closed_form_columns(t, {**cf, "omega_table": omega})
    return float(max(np.max(np.abs(cols[c] - printed[c])) for c in TABLE1_COLUMNS))


def deviation_xa_d_dt(cf: dict) -> float:
    """Max |xa - Table 1's xa| if xa were d/dt as labelled (it is d/dh)."""
    printed = paper_table1()
    t = np.asarray(printed["t"])
    xa = cf["omega_table"] * closed_form_columns(t, cf)["xa"]  # d/dt = (T/300) d/dh
    return float(np.max(np.abs(xa - np.asarray(printed["xa"]))))
