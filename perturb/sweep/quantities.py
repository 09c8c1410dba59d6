"""The store's variables: one :class:`Variable` per quantity, its dimensions, type and meaning.

Every variable has the swept parameters as its leading dimensions, then its own
(``component``: the state's names, ``time``: the times asked for, ``multiplier``: the Floquet
multipliers, ``check``: the verdict's checks). A variable whose name is also a swept parameter's
(Duffing's ``amplitude``...) is stored as ``sweep_<name>``: the parameters keep their names as
coordinates, so that ``ds.sel(amplitude=1.2)`` works.
"""

from __future__ import annotations

import json

import numpy as np
from attrs import field, frozen

from perturb.oracle import OrbitStatus, TrajectoryStatus
from perturb.sweep.status import NOT_COMPUTED, PointStatus, coding_attrs
from perturb.validation import Verdict
from perturb.validation.verdict import measurement_checks

__all__ = ["LEGACY_NONE", "TIMINGS", "Variable", "check_names", "stored_name", "variables"]

#: The value of a legacy status code (trajectory, orbit: 0 success, negative failure) where the
#: JSON has null (nothing ran) or nothing was computed.
LEGACY_NONE = 127

#: What a task returns beside the variables: its wall and CPU seconds (not stored).
TIMINGS = ("seconds", "cpu")

#: Code of a check's outcome in ``check_passed``: passed, failed, could not run.
CHECK_CODES = {True: 1, False: 0, None: NOT_COMPUTED}


@frozen
class Variable:
    """One quantity of the store.

    Attributes
    ----------
    name : str
    dims : tuple of str
        Its own dimensions, after the swept ones.
    dtype : str
        numpy dtype (``"str"`` for text).
    fill : object
        Its value where nothing was computed.
    attrs : dict
        ``long_name``, ``units`` or the coding of an enum.
    validation : bool
        Whether it is filled only by a validated sweep.
    """

    name: str
    dims: tuple = field(converter=tuple)
    dtype: str
    fill: object
    attrs: dict = field(factory=dict)
    validation: bool = False


def check_names() -> tuple[str, ...]:
    """The names of the verdict's checks (``existence``, ``orbit_error``, ...), from the rule."""
    return tuple(check.name for check in measurement_checks(None, None, 1.0))


def _legacy(enum_type, what: str) -> dict:
    meanings = {str(LEGACY_NONE): f"no {what} ran"}
    meanings.update({str(m.code): str(m.value) for m in enum_type})
    return {
        "long_name": f"{what} status (the JSON's integer code)",
        "meanings": json.dumps(meanings),
    }


def variables(validate: bool) -> tuple[Variable, ...]:
    """The variables of a sweep (with the validation's when ``validate``)."""
    nan = np.nan
    out = [
        Variable("status", (), "int8", NOT_COMPUTED, coding_attrs(PointStatus, "point status")),
        Variable(
            "reason", (), "str", "", {"long_name": "why the point failed (empty if it did not)"}
        ),
        Variable("warnings", (), "str", "", {"long_name": "warnings raised at the point"}),
        Variable("epsilon", (), "float64", nan, {"long_name": "expansion parameter ε"}),
        Variable("period", (), "float64", nan, {"long_name": "analytic period (physical time)"}),
        Variable(
            "frequency", (), "float64", nan, {"long_name": "analytic angular frequency 2π/period"}
        ),
        Variable(
            "amplitude",
            ("component",),
            "float64",
            nan,
            {"long_name": "half the range of each component over one analytic period"},
        ),
        Variable("state", ("time", "component"), "float64", nan, {"long_name": "analytic state"}),
    ]
    if validate:
        out += [
            Variable("verdict", (), "int8", NOT_COMPUTED, coding_attrs(Verdict, "verdict"), True),
            Variable(
                "verdict_reason", (), "str", "", {"long_name": "the verdict's sentence"}, True
            ),
            Variable(
                "accurate_order",
                (),
                "int8",
                NOT_COMPUTED,
                {
                    "long_name": "with the verdict lower_order: the k of 'accurate to "
                    "O(eps^(k+1))' (-1 otherwise)"
                },
                True,
            ),
            Variable(
                "completed",
                (),
                "int8",
                NOT_COMPUTED,
                {"long_name": "the validation ran to the end (1), failed numerically (0)"},
                True,
            ),
            Variable(
                "trajectory_status",
                (),
                "int8",
                LEGACY_NONE,
                _legacy(TrajectoryStatus, "integration"),
                True,
            ),
            Variable(
                "orbit_status", (), "int8", LEGACY_NONE, _legacy(OrbitStatus, "shooting"), True
            ),
            Variable(
                "orbit_error",
                (),
                "float64",
                nan,
                {"long_name": "distance of the analytic orbit from the true one (relative)"},
                True,
            ),
            Variable(
                "period_error",
                (),
                "float64",
                nan,
                {"long_name": "(analytic period - true period) / true period"},
                True,
            ),
            Variable(
                "initial_state_error",
                (),
                "float64",
                nan,
                {"long_name": "initial-state error against the true orbit (relative)"},
                True,
            ),
            Variable("true_period", (), "float64", nan, {"long_name": "true orbit's period"}, True),
            Variable(
                "resolution",
                (),
                "float64",
                nan,
                {"long_name": "uncertainty of the true orbit found (relative)"},
                True,
            ),
            Variable(
                "order_slope",
                (),
                "float64",
                nan,
                {"long_name": "measured slope of log(error) against log(eps)"},
                True,
            ),
            Variable(
                "floquet_real",
                ("multiplier",),
                "float64",
                nan,
                {"long_name": "Floquet multipliers, real part (sorted by distance from 1)"},
                True,
            ),
            Variable(
                "floquet_imag",
                ("multiplier",),
                "float64",
                nan,
                {"long_name": "Floquet multipliers, imaginary part"},
                True,
            ),
            Variable(
                "check_value", ("check",), "float64", nan, {"long_name": "each check's value"}, True
            ),
            Variable(
                "check_passed",
                ("check",),
                "int8",
                NOT_COMPUTED,
                {
                    "long_name": "each check's outcome",
                    "meanings": json.dumps({"1": "passed", "0": "failed", "-1": "could not run"}),
                },
                True,
            ),
        ]
    out.append(
        Variable(
            "session",
            (),
            "int16",
            0,
            {"long_name": "the run of the sweep that computed the point (0: not yet)"},
        )
    )
    return tuple(out)


def stored_name(name: str, swept: tuple[str, ...]) -> str:
    """The name of variable ``name`` in a store sweeping ``swept`` (see the module docstring)."""
    return f"sweep_{name}" if name in swept else name
