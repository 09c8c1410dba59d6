"""The corpus, continued: hostile calls of find_families, validate and the oracle's constructors.

Same rules as :mod:`tests.engine.api_corpus` (refused with the argument named, or answered).
"""

from __future__ import annotations

import numpy as np

from perturb import find_families, validate
from perturb.oracle import RK4, Heyoka, Scipy, choose, find_periodic_orbit
from tests.engine.api_corpus import NAN, Case, _c, duffing

_S = duffing
CASES_MORE: list[Case] = []
# find_families and validate
CASES_MORE += [
    _c("find_families order=0", lambda: find_families(_S(), 0), "order"),
    _c("find_families branch", lambda: find_families(_S(), 1, branch=1), "branch"),
    _c("find_families unknown option", lambda: find_families(_S(), 1, foo=1), "foo"),
    _c("find_families system=None", lambda: find_families(None), "system"),
    _c(
        "find_families amplitudes unknown",
        lambda: find_families(_S(), 1, amplitudes={"y": 1}),
        "amplitudes",
    ),
    _c("validate order=0", lambda: validate(_S(), 0, values={"epsilon": 0.1}), "order"),
    _c(
        "validate periods=nan",
        lambda: validate(_S(), periods=NAN, values={"epsilon": 0.1}),
        "periods",
    ),
    _c("validate tol=-1", lambda: validate(_S(), tol=-1, values={"epsilon": 0.1}), "tol"),
    _c("validate rtol=str", lambda: validate(_S(), rtol="a", values={"epsilon": 0.1}), "rtol"),
    _c(
        "validate integrator unknown",
        lambda: validate(_S(), integrator="zz", values={"epsilon": 0.1}),
        "integrator",
    ),
    _c("validate epsilon=nan", lambda: validate(_S(), values={"epsilon": NAN}), "values"),
    _c(
        "validate values unknown",
        lambda: validate(_S(), values={"epsilon": 0.1, "zz": 1}),
        "values",
    ),
    _c("validate problem=None", lambda: validate(None), "problem"),
    _c(
        "validate options unknown",
        lambda: validate(_S(), values={"epsilon": 0.1}, options={"foo": 1}),
        "foo",
    ),
    _c(
        "validate samples_per_period=2",
        lambda: validate(_S(), samples_per_period=2, values={"epsilon": 0.1}),
        "samples_per_period",
    ),
    _c(
        "validate initial_state nan",
        lambda: validate(_S(), initial_state=[NAN, 0], values={"epsilon": 0.1}),
        "initial_state",
    ),
]
# oracle constructors and functions
_HARMONIC = lambda y: np.array([y[1], -y[0]])  # noqa: E731
CASES_MORE += [
    _c("RK4 steps_per_unit=nan", lambda: RK4(steps_per_unit=NAN), "steps_per_unit"),
    _c("RK4 steps_per_unit=str", lambda: RK4(steps_per_unit="a"), "steps_per_unit"),
    _c("RK4 n_steps=1.5", lambda: RK4(n_steps=1.5), "n_steps"),
    _c("RK4 n_steps=True", lambda: RK4(n_steps=True), "n_steps"),
    _c("Scipy method=foo", lambda: Scipy(method="foo"), "method"),
    _c("Scipy method=None", lambda: Scipy(method=None), "method"),
    _c("Scipy rtol=nan", lambda: Scipy(rtol=NAN), "rtol"),
    _c("Scipy rtol=str", lambda: Scipy(rtol="a"), "rtol"),
    _c("Scipy max_steps=str", lambda: Scipy(max_steps="a"), "max_steps"),
    _c("Scipy max_steps=1.5", lambda: Scipy(max_steps=1.5), "max_steps"),
    _c("Scipy max_steps=nan", lambda: Scipy(max_steps=NAN), "max_steps"),
    _c("Scipy atol=-1", lambda: Scipy(atol=-1), "atol"),
    _c("Scipy y_scale=[nan]", lambda: Scipy(y_scale=[NAN]), "y_scale"),
    _c("Heyoka tol=nan", lambda: Heyoka(tol=NAN), "tol"),
    _c("Heyoka fp_type=quad", lambda: Heyoka(fp_type="quad"), "fp_type"),
    _c("Heyoka max_steps=str", lambda: Heyoka(max_steps="a"), "max_steps"),
    _c("Heyoka high_precision=str", lambda: Heyoka(high_precision="yes"), "high_precision"),
    _c("Heyoka compact_mode=str", lambda: Heyoka(compact_mode="yes"), "compact_mode"),
    _c("choose unknown", lambda: choose("zz"), "integrator"),
    _c("choose 5", lambda: choose(5), "integrator"),
    _c("choose rtol=nan", lambda: choose("dop853", rtol=NAN), "rtol"),
    _c("choose max_steps=str", lambda: choose("dop853", max_steps="a"), "max_steps"),
    _c("integrate t_span nan", lambda: RK4().integrate(_HARMONIC, (0, NAN), [1, 0]), "t_span"),
    _c("integrate y0 nan", lambda: Scipy().integrate(_HARMONIC, (0, 1), [NAN, 0]), "y0"),
    _c("integrate rhs None", lambda: Scipy().integrate(None, (0, 1), [1, 0]), "rhs"),
    _c(
        "shoot y0 nan",
        lambda: find_periodic_orbit(_HARMONIC, [NAN, 0], 6.0, section_index=1),
        "y0_guess",
    ),
    _c(
        "shoot period nan",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], NAN, section_index=1),
        "period_guess",
    ),
    _c(
        "shoot period str",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], "6", section_index=1),
        "period_guess",
    ),
    _c(
        "shoot section 5",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index=5),
        "section_index",
    ),
    _c(
        "shoot section str",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index="a"),
        "section_index",
    ),
    _c(
        "shoot tol str",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index=1, tol="a"),
        "tol",
    ),
    _c(
        "shoot max_iter 0",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index=1, max_iter=0),
        "max_iter",
    ),
    _c(
        "shoot direction 2",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index=1, direction=2),
        "direction",
    ),
    _c(
        "shoot y_scale nan",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index=1, y_scale=NAN),
        "y_scale",
    ),
    _c(
        "shoot integrator unknown",
        lambda: find_periodic_orbit(_HARMONIC, [1, 0], 6.0, section_index=1, integrator="zz"),
        "integrator",
    ),
]
