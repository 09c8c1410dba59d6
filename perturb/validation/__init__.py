"""Check a problem's analytic periodic solution against the true motion: :func:`validate`.

The verdict rests on three measurements, each a number against its tolerance
(``docs/validation.md``): a true periodic orbit exists near the analytic one (existence), the
analytic orbit and period are within ``tol`` of it (accuracy), and the error falls like ε^(N+1)
along a scan of the problem's own small parameter (order).  Problems take part through the typed
:class:`Model` protocol; :class:`SystemModel` adapts a bare :class:`perturb.QuasilinearSystem`.

Modules: :mod:`.model` (the protocol), :mod:`.system_model` (a bare system as a model),
:mod:`.capabilities` (optional physics a model declares), :mod:`.truth` (the equations a
model is checked against, and the model at another ε), :mod:`.frames` (what a free and a driven
case solve, check and print: one table), :mod:`.checks` and :mod:`.orbit` (the measurements),
:mod:`.verdict` (the rule), :mod:`.report` (the result objects), :mod:`.validate` (orchestration).
"""

from perturb._defaults import (
    AMPLITUDE_FLOOR,
    DEFAULT_PERIODS,
    DEFAULT_RTOL,
    DEFAULT_TOL,
    EPSILON_LIMIT,
    ERROR_FLOOR,
    ESTIMATE_FAILED_MAX_STEPS,
    FLOQUET_TOL,
    INVALID_MAX_STEPS,
    KNOB_PROBE,
    MAX_OUTPUT_SAMPLES,
    MAX_RELATIVE_ERROR,
    MULTIPLIER_FLOOR,
    ORBIT_RESOLUTION_LIMIT,
    SAMPLES_PER_PERIOD,
    SHOOTING_ITERATIONS,
    SHOOTING_PRECISION,
    SLOPE_FACTORS,
    SLOPE_TOLERANCE,
    STIFF_RTOL,
    STIFFNESS_SAMPLES,
    STIFFNESS_THRESHOLD,
)
from perturb.validation._quasilinear import quasilinear_state_names, state_along
from perturb.validation.capabilities import has_euler_angles
from perturb.validation.checks import stiffness_indicator
from perturb.validation.model import (
    Equations,
    Integrals,
    Model,
    OrbitEstimate,
    ShootingSetup,
)
from perturb.validation.report import (
    Check,
    Condition,
    InvariantDrift,
    OrbitCheck,
    SlopeFit,
    Stiffness,
    ValidationReport,
    Verdict,
)
from perturb.validation.system_model import SystemModel, as_model
from perturb.validation.truth import (
    original_equations,
    original_rhs,
    system_equations,
    with_epsilon,
)
from perturb.validation.validate import validate

__all__ = [
    "AMPLITUDE_FLOOR",
    "DEFAULT_PERIODS",
    "DEFAULT_RTOL",
    "DEFAULT_TOL",
    "EPSILON_LIMIT",
    "ERROR_FLOOR",
    "ESTIMATE_FAILED_MAX_STEPS",
    "FLOQUET_TOL",
    "INVALID_MAX_STEPS",
    "KNOB_PROBE",
    "MAX_OUTPUT_SAMPLES",
    "MAX_RELATIVE_ERROR",
    "MULTIPLIER_FLOOR",
    "ORBIT_RESOLUTION_LIMIT",
    "SAMPLES_PER_PERIOD",
    "SHOOTING_ITERATIONS",
    "SHOOTING_PRECISION",
    "SLOPE_FACTORS",
    "SLOPE_TOLERANCE",
    "STIFFNESS_SAMPLES",
    "STIFFNESS_THRESHOLD",
    "STIFF_RTOL",
    "Check",
    "Condition",
    "Equations",
    "Integrals",
    "InvariantDrift",
    "Model",
    "quasilinear_state_names",
    "state_along",
    "OrbitCheck",
    "OrbitEstimate",
    "ShootingSetup",
    "SlopeFit",
    "Stiffness",
    "SystemModel",
    "ValidationReport",
    "Verdict",
    "as_model",
    "stiffness_indicator",
    "has_euler_angles",
    "original_equations",
    "original_rhs",
    "system_equations",
    "validate",
    "with_epsilon",
]
