"""The seed paper's data: its inputs (31), its printed constants (32) and its Table 1.

The printed numbers are kept as the paper prints them (strings where the last printed digit sets the
tolerance).  :func:`derived_constants` recomputes (32) from (31) with the project's own
nondimensionalisation and says, per constant, whether the printed value is reproduced.

References
----------
.. [1] The seed paper, equations (4), (31), (32) and Table 1.
"""

from __future__ import annotations

import csv
import io
import math
from decimal import Decimal
from importlib import resources

from problems.rigid_body.equations import NondimensionalParameters, RigidBodyParameters

__all__ = [
    "PAPER_CITATION",
    "PAPER_INPUTS",
    "PRINTED_CONSTANTS",
    "TABLE1_COLUMNS",
    "TABLE1_T_END",
    "derived_constants",
    "half_unit",
    "paper_body",
    "paper_scaled",
    "paper_table1",
    "table1_tolerance",
]

#: What we know of the seed paper's identity. Our copy is a plain-text extraction that starts at the
#: abstract, so the title is the one we cite it by (its subject in its own words) and the authors
#: and the year are not known to us; every equation number (NN) printed by the reproduction is the
#: paper's, Table 1 is its table, and E#/C#/U# are our errata, argued in ``docs/paper-errata.md``.
PAPER_CITATION = {
    "title": (
        "Periodic solutions of a disk about a fixed point in a Newtonian force field and gravity "
        "(large parameter technique, slow spin)"
    ),
    "authors": "not in our copy of the paper",
    "year": "not in our copy of the paper",
    "errata": "docs/paper-errata.md",
}

#: Input data (31) of the paper.  ``g`` is printed among the *derived* constants (32), but nothing
#: in (31) determines it; it is an input (with it, c of (32) is reproduced to all printed digits).
#: z0 is not given; the disk's centre of mass is taken in its plane, z0 = 0.
PAPER_INPUTS = {
    "A": 9.0,
    "B": 11.0,
    "C": 20.0,
    "x0": 1.0,
    "y0": 6.0,
    "R": 2000.0,
    "M": 200.0,
    "gamma3_0": 7e-6,
    "lambda": 0.6,
    "r0": 1.3e-5,
    "T": 18.78775142,
    "g": 1.5e-7,
}

#: Derived constants (32) exactly as printed (strings: their last digit sets the tolerance).
PRINTED_CONSTANTS = {
    "C1": "1.0E-01",
    "ell": "6.082763",
    "x0p": "1.643990E-01",
    "y0p": "9.863939E-01",
    "g": "1.500000E-07",
    "c": "3.020620E-03",
    "mu": "2.323554E06",
    "a": "4.5E-01",
    "b": "5.5E-01",
    "k": "2.465985E-05",
    "chi2": "-1.726189E-10",
}

#: Table 1 columns in the paper's order.
TABLE1_COLUMNS = ("p2a", "gamma2a", "xa", "ya")

#: Floor of the Table 1 tolerance: the table carries 7 significant digits (single precision), so
#: entries of size ~7 are good to ~5e-6; 1e-5 leaves a factor 2 for the paper's own round-off.
TABLE1_ABS_FLOOR = 1e-5

#: Significant digits of the plain (non-E) entries of Table 1: the table is printed with %.7g
#: (trailing zeros dropped), so "1" means 1.000000 and is *not* good to only half a unit.
TABLE1_SIGNIFICANT_DIGITS = 7

#: Number of rows of Table 1 (t = 0, 10, ..., 300) and the end of its time column.
TABLE1_T_END = 300.0

#: Notes attached to the constants whose reading needs one.
_CONSTANT_NOTES = {
    "g": "an input in fact: nothing in (31) fixes it; it reproduces c",
    "mu": "printed definition mu = c*sqrt(gamma0'')/r0 (4) does NOT give the printed value",
    "chi2": "undefined in the text; equals -k*gamma0''",
}


def half_unit(text: str) -> float:
    """Half a unit of the last printed digit of ``text`` (e.g. '2.79E-01' -> 0.005)."""
    return 0.5 * 10.0 ** Decimal(text.strip()).as_tuple().exponent


def table1_tolerance(text: str) -> float:
    """Tolerance of one Table 1 entry: max(1e-5, half a unit of its last significant digit).

    E-notation entries (e.g. '4.30E-01', 3 digits) are good to half a unit of the printed last
    digit.  Plain entries are printed with 7 significant digits and trailing zeros dropped, so
    their last significant digit is the 7th.
    """
    if "e" in text.lower():
        return max(TABLE1_ABS_FLOOR, half_unit(text))
    value = abs(float(text))
    if value == 0.0:
        return TABLE1_ABS_FLOOR
    exponent = math.floor(math.log10(value)) - TABLE1_SIGNIFICANT_DIGITS + 1
    return max(TABLE1_ABS_FLOOR, 0.5 * 10.0**exponent)


def paper_table1() -> dict[str, list]:
    """The printed Table 1 (shipped copy): ``{"t": [...], col: [float], col + "_text": [str]}``."""
    text = resources.files("problems.rigid_body.data").joinpath("table1.csv").read_text()
    rows = list(csv.DictReader(io.StringIO(text)))
    out: dict[str, list] = {"t": [float(r["t"]) for r in rows]}
    for col in TABLE1_COLUMNS:
        out[col] = [float(r[col]) for r in rows]
        out[col + "_text"] = [r[col].strip() for r in rows]
    return out


def paper_body() -> RigidBodyParameters:
    """The paper's body (31) in physical units (z0 = 0)."""
    p = PAPER_INPUTS
    return RigidBodyParameters(
        A=p["A"], B=p["B"], C=p["C"], x0=p["x0"], y0=p["y0"], z0=0.0, M=p["M"], g=p["g"], R=p["R"]
    )


def paper_scaled() -> NondimensionalParameters:
    """The paper's body scaled by its initial spin r0 (a, b, k, x0', y0' and eps = c/r0)."""
    return NondimensionalParameters.from_dimensional(paper_body(), PAPER_INPUTS["r0"])


def derived_constants() -> dict[str, dict]:
    """The constants (32) recomputed from (31), beside the printed values.

    Returns
    -------
    dict
        ``name -> {"computed", "printed", "matches", "note"}`` for every printed constant, plus
        ``mu_1e4_c_over_r0`` (the reading that reproduces the printed mu) and ``eps`` (the
        consistent expansion parameter c/r0, not printed).  ``matches`` is True when the computed
        value is within half a unit of the printed last digit.
    """
    body, nd = paper_body(), paper_scaled()
    r0, g3 = PAPER_INPUTS["r0"], PAPER_INPUTS["gamma3_0"]
    c = nd.eps * r0
    computed = {
        "C1": (body.B - body.A) / body.C,
        "ell": body.arm,
        "x0p": nd.x0p,
        "y0p": nd.y0p,
        "g": body.g,
        "c": c,
        "mu": c * math.sqrt(g3) / r0,
        "a": nd.a,
        "b": nd.b,
        "k": nd.k,
        "chi2": -nd.k * g3,
    }
    out = {}
    for name, value in computed.items():
        printed = float(PRINTED_CONSTANTS[name])
        ok = abs(value - printed) <= half_unit(PRINTED_CONSTANTS[name])
        out[name] = {
            "computed": value,
            "printed": printed,
            "matches": bool(ok),
            "note": _CONSTANT_NOTES.get(name, ""),
        }
    mu_1e4 = 1e4 * c / r0
    mu_printed = float(PRINTED_CONSTANTS["mu"])
    out["mu_1e4_c_over_r0"] = {
        "computed": mu_1e4,
        "printed": mu_printed,
        "matches": bool(abs(mu_1e4 - mu_printed) <= half_unit(PRINTED_CONSTANTS["mu"])),
        "note": "1e4*c/r0 reproduces the printed mu; no constant of (31) supplies the 1e4",
    }
    out["eps"] = {
        "computed": nd.eps,
        "printed": None,
        "matches": None,
        "note": "consistent expansion parameter eps = c/r0 (the paper's 1/mu): NOT small",
    }
    return out
