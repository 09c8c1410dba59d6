"""Rigid body about a fixed point: Euler–Poisson equations and their reduction."""

# numeric hands the functions that moved to it back to equations, for the old imports: load it
# with the package, so that ``from problems.rigid_body.equations import full_rhs`` finds them.
from problems.rigid_body import numeric as _numeric  # noqa: F401
